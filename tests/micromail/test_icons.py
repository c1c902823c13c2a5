"""MicroMail's icons: each drawn once per page, used by every row that shows it."""

from __future__ import annotations

import pytest
from django.test import Client

pytestmark = pytest.mark.django_db


def test_a_page_carries_the_drawing_of_every_icon_it_uses_once(mail_run):
    html = Client().get(f"/r/{mail_run.token}/micromail/?folder=inbox").content.decode()
    used = {"flag", "pin", "paperclip", "exclamation-mark"}
    for name in used:
        assert f'<use href="#icon-{name}">' in html
        assert html.count(f'<symbol id="icon-{name}" viewBox="0 0 24 24">') == 1
    assert "<path" not in html.split('class="icon-sprite"')[0]  # no drawing repeated per row

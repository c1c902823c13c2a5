"""A refused action is a page of the site that names the reason, not a bare text response."""

from __future__ import annotations

import pytest
from django.test import Client

pytestmark = pytest.mark.django_db


def test_a_refused_action_answers_a_page_naming_the_reason(mail_run):
    response = Client().post(f"/r/{mail_run.token}/micromail/emails/no-such-mail/flag")
    html = response.content.decode()
    assert response.status_code == 404 and response["Content-Type"].startswith("text/html")
    assert 'role="alert"' in html and "no email &#x27;no-such-mail&#x27; in this mailbox" in html
    assert f'href="/r/{mail_run.token}/micromail/"' in html  # a way back

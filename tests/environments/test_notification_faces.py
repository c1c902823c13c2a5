"""A notification shows the face or mark of whoever it is from (finding: MicroDin's job
notification showed a person's face, MicroTube's comment notification the user's own channel,
and channels the run had not loaded all showed MicroTube's own mark)."""

from __future__ import annotations

import pytest
from django.test import Client

from apps.kit.links import environment_root
from apps.media import links
from apps.scenarios.library import get_scenario
from events import lifecycle

pytestmark = pytest.mark.django_db


def page_of(scenario_id: str, path: str, at: float = 0.0) -> str:
    run = lifecycle.create_run(get_scenario(scenario_id).to_run_spec())
    lifecycle.advance(run, at)
    response = Client().get(f"{environment_root(run)}/{path}")
    assert response.status_code == 200
    return response.content.decode()


def test_a_job_notification_shows_the_employers_logo():
    page = page_of("microdin-jobs-absolute-passive", "notifications/", at=600.0)  # it arrived
    assert "New job for you: Product Manager, Integrations at Quillfeather Software" in page
    assert links.logo_url("Quillfeather Software") in page


def test_a_comment_notification_shows_the_commenter_and_each_channel_its_own_mark():
    page = page_of("microtube-channel-noop", "notifications")
    assert "Maya Okonjo commented on your video" in page
    assert links.avatar_url("Maya Okonjo") in page
    for channel in ("Kitchen Table Code", "Daily Byte", "Brew Lab", "Sprint Sketches"):
        assert links.logo_url(channel) in page, channel
    assert links.logo_url("MicroTube") not in page

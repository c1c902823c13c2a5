"""A page of a run that shows nothing (an item unknown or not arrived yet) is a 404 page of the
site itself: the environment's shell, the reason, a way back — not a bare error page, which an
agent judging a screenshot would take for a broken site."""

from __future__ import annotations

import pytest

from apps.kit.links import environment_root
from apps.scenarios.library import get_dev_scenario
from events import lifecycle
from events.models import ClockMode

pytestmark = pytest.mark.django_db


@pytest.mark.parametrize(
    "environment, path, reason",
    [
        ("micromail", "/?folder=inbox&email=not-arrived-yet", "no such email"),
        ("microgram", "/p/not-posted-yet/", "no such post"),
        ("microhub", "/issues/999999", "no such issue"),
    ],
)
def test_a_missing_item_is_a_404_page_of_the_site(client, environment, path, reason):
    run = lifecycle.create_run(
        get_dev_scenario(environment).to_run_spec(), clock_mode=ClockMode.VIRTUAL
    )
    root = environment_root(run)
    response = client.get(root + path)
    assert response.status_code == 404
    html = response.content.decode()
    assert "<h1>This page does not exist</h1>" in html
    assert f'<p role="alert" class="rejected-reason">{reason}</p>' in html
    assert f'href="{root}/"' in html  # the way back to the environment's home
    assert 'class="shell' in html or "site/shell.css" in html  # the site's own shell


def test_an_action_refused_is_not_called_a_missing_page(client):
    run = lifecycle.create_run(
        get_dev_scenario("micromail").to_run_spec(), clock_mode=ClockMode.VIRTUAL
    )
    response = client.post(
        f"/r/{run.token}/actions",
        {"action": "flag", "payload": {"email_id": "nope"}},
        content_type="application/json",
    )
    assert response.status_code == 404
    assert "This page does not exist" not in response.content.decode()

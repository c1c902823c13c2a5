"""An address under a run's environment that no page answers is the run's own "does not exist"
page, in the site's shell with a way back (finding: a wrong link led to Django's bare 404)."""

from __future__ import annotations

import pytest
from django.test import Client

from apps.kit.links import environment_root
from apps.scenarios.library import get_scenario
from events import lifecycle

pytestmark = pytest.mark.django_db


@pytest.mark.parametrize("rest", ["docs/api.md", "no/such/page", "inbox/"])
def test_an_unknown_address_under_an_environment_is_the_sites_not_found_page(rest):
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    root = environment_root(run)
    response = Client().get(f"{root}/{rest}")
    assert response.status_code == 404
    page = response.content.decode()
    assert "This page does not exist" in page and f'href="{root}/"' in page
    assert "MicroMail" in page


def test_another_environments_address_under_the_token_is_still_refused():
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    assert Client().get(f"/r/{run.token}/microhub/whatever").status_code == 404

"""A pushed region is the full page's region, whitespace and all: an agent that reads the page's
text or markup, not only its pixels, sees a change only where the page changed.

Every environment's start page of its first scenario, some way into the run: the regions a push
would carry against the same regions of a full render of the same moment.
"""

from __future__ import annotations

import json

import pytest
from bs4 import BeautifulSoup
from django.test import Client

from apps.kit.live import render_update, without_csrf_tokens
from apps.scenarios.library import scenario_library
from events.models import Run

pytestmark = pytest.mark.django_db

AT = 120.0  # simulated seconds: a few of every scenario's entries have fired


def first_scenario_of_each_environment() -> list[str]:
    library = scenario_library()
    firsts: dict[str, str] = {}
    for name in sorted(library):
        firsts.setdefault(library[name].to_run_spec()["environment"], name)
    return sorted(firsts.values())


def by_id(html: str, ids: list[str]) -> dict[str, str]:
    """Each element's markup as parsed and written back (one parser for both sides)."""
    soup = BeautifulSoup(without_csrf_tokens(html), "html.parser")
    found = {}
    for element_id in ids:
        element = soup.find(id=element_id)
        assert element is not None, f"no #{element_id}"
        element.attrs.pop("hx-swap-oob", None)  # the swap instruction, not the page
        found[element_id] = str(element)
    return found


@pytest.mark.parametrize("scenario", first_scenario_of_each_environment())
def test_a_pushed_region_is_the_full_renders_region(scenario):
    client = Client()
    created = client.post(
        "/api/runs/",
        json.dumps({"scenario": scenario, "clock_mode": "virtual"}),
        content_type="application/json",
    ).json()
    advanced = client.post(
        f"/api/runs/{created['id']}/advance/",
        json.dumps({"time": AT}),
        content_type="application/json",
    )
    assert advanced.status_code == 200, advanced.content
    page = client.get(created["task_url"], follow=True)
    assert page.status_code == 200
    url = page.request["PATH_INFO"]

    update = render_update(Run.objects.get(pk=created["id"]), url)

    ids = [region_id for region_id, _ in update.regions]
    assert ids, f"{url} has no live region"
    assert by_id(update.html, ids) == by_id(page.content.decode(), ids)

"""The live protocol is a pure read (finding 4): it renders a page's regions and never performs
what opening the page would — starting the clock, a contact, an action, an implicit action.

Generic: every URL under a run's prefix (from the URL resolver, so a new environment's pages are
covered), and every page where a scenario's solution is carried out (each environment's
`Action.page`), over polling and over the websocket.
"""

from __future__ import annotations

import pytest
from asgiref.sync import async_to_sync
from channels.testing import WebsocketCommunicator
from django.test import Client
from django.urls import URLPattern, URLResolver, get_resolver

from apps.kit.links import contact_path, environment_root, live_path
from events import lifecycle
from events.commands import current_state
from events.models import ClockMode, Event, Run, RunStatus
from events.registry import get_environment
from sentinel_site.urls import RUN_PREFIX
from tests.environments.cases import Case, all_cases, params
from tests.environments.oracle import page_step


def run_routes() -> list[str]:
    """Every route under a run's prefix whose only parameter is the token."""
    found: list[str] = []

    def walk(patterns, prefix: str) -> None:
        for entry in patterns:
            route = prefix + str(entry.pattern)
            if isinstance(entry, URLResolver):
                walk(entry.url_patterns, route)
            elif isinstance(entry, URLPattern) and route.startswith(RUN_PREFIX):
                rest = route[len(RUN_PREFIX) :]
                if "<" not in rest:
                    found.append(rest)

    walk(get_resolver().url_patterns, "")
    return sorted(set(found))


def footprint(run: Run) -> tuple:
    """What an action, a contact or a started clock would change."""
    run.refresh_from_db()
    return (
        run.status,
        run.started_at,
        run.sim_time,
        list(Event.objects.filter(run_id=run.pk).values_list("seq", "kind", "type")),
    )


def poll(run: Run, url: str):
    return Client().get(live_path(run), {"url": url, "seq": -1})


def one_case_per_environment() -> list:
    first: dict[str, Case] = {}
    for case in all_cases(upstream=False):
        first.setdefault(case.environment, case)
    return [pytest.param(case, id=name) for name, case in sorted(first.items())]


@pytest.mark.django_db
@pytest.mark.parametrize("case", one_case_per_environment())
def test_polling_any_url_of_a_run_changes_nothing(case):
    """A ready live run: the task URL would start its clock, the contact URL complete it."""
    run = lifecycle.create_run(case.load().to_run_spec(), clock_mode=ClockMode.LIVE)
    routes = run_routes()
    assert {"start", "contact", "actions"} <= set(routes)
    before = footprint(run)
    for route in routes:
        url = f"/r/{run.token}/{route}"
        response = poll(run, url)
        assert response.status_code in (200, 204, 400, 404), (url, response.status_code)
        assert footprint(run) == before, f"live?url={url} changed the run"
    assert run.status == RunStatus.READY


@pytest.mark.django_db
@pytest.mark.parametrize("case", params(needs_action=True, upstream=False))
def test_polling_the_page_of_every_solution_step_changes_nothing(case):
    """Opening the page is the action for some steps (an implicit action: opening marks read)."""
    scenario = case.load()
    run = lifecycle.create_run(scenario.to_run_spec(), clock_mode=ClockMode.VIRTUAL)
    # Everything the steps refer to exists: at the end, or while an ephemeral condition holds.
    until = scenario.condition_until
    held = scenario.event_timeline_end if until is None else (scenario.condition_at + until) / 2
    lifecycle.advance(run, held)
    environment = get_environment(run.environment)
    state = current_state(run)
    before = footprint(run)
    for step in scenario.solution:
        url = f"{environment_root(run)}/{page_step(environment, state, step).path}"
        assert poll(run, url).status_code == 200, url
        assert footprint(run) == before, f"live?url={url} performed {step['action']}"


@pytest.mark.django_db(transaction=True)
def test_a_websocket_asking_for_the_contact_or_task_url_changes_nothing(tally_spec, settings):
    settings.CHANNEL_LAYERS = {"default": {"BACKEND": "channels.layers.InMemoryChannelLayer"}}
    from channels.layers import channel_layers

    channel_layers.backends.clear()
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.LIVE)
    before = footprint(run)

    async def story():
        from sentinel_site.asgi import router

        socket = WebsocketCommunicator(router, live_path(run))
        connected, _ = await socket.connect(timeout=10)
        assert connected
        for url in (contact_path(run), f"/r/{run.token}/start"):
            await socket.send_json_to({"url": url, "seq": 0})
            assert await socket.receive_nothing(timeout=1)  # no regions: not a live page
        await socket.disconnect()

    try:
        async_to_sync(story)()
    finally:
        channel_layers.backends.clear()
    assert footprint(run) == before

"""Is the trigger there to be seen? The watched page just before and at `condition_at`.

An agent that judges what it sees can only be graded fairly if the change it must notice shows
on the page its prompt tells it to watch (`watch_page`, else the start page). This check folds
the timeline in memory, renders that page with the environment's own view on a virtual clock
0.01 s before `condition_at` and at it (apps.kit.probe: no run stored, nothing logged), and
compares the text a person sees (apps.kit.visible). Shared by `checkscenarios`, the admin's
dry run, `bench validate` and the test over every scenario file.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from apps.kit.probe import (
    NotRendered,
    environment_path,
    probe_run,
    render_probe,
    state_at_time,
)
from apps.kit.visible import text_difference, visible_text
from apps.scenarios.format import Scenario
from events.registry import UnknownEnvironment, get_environment

JUST_BEFORE = 0.01  # simulated seconds before condition_at: the page as the agent last saw it


@dataclass(frozen=True)
class WatchCheck:
    scenario: str  # where the scenario comes from (its file), for reports
    page: str  # the watched page, as the scenario writes it
    condition_at: float
    changes: bool
    detail: str  # one line: where the text changed, or why it did not / could not be checked

    def __str__(self) -> str:
        return self.detail


def watch_check(
    environment_name: str,
    page: str,
    condition_at: float,
    events: Iterable[Mapping[str, Any]],
    event_timeline_end: float,
    *,
    spec: dict[str, Any] | None = None,
    catalog_dir=None,
    source: str = "",
) -> WatchCheck:
    """Render `page` just before and at `condition_at` of the timeline `events`
    ({time, type, payload}, in order) and say whether its visible text changes."""

    def result(changes: bool, detail: str) -> WatchCheck:
        return WatchCheck(source, page, condition_at, changes, detail)

    try:
        environment = get_environment(environment_name)
    except UnknownEnvironment as error:
        return result(False, f"cannot render: {error}")
    if not environment.urlconf:
        return result(False, f"cannot render: {environment_name} has no pages")
    try:
        path = environment_path(page, environment_name)
    except NotRendered as error:
        return result(False, str(error))
    run = probe_run(environment_name, spec or {})
    timeline = list(events)

    def text_at(at: float) -> str:
        state = state_at_time(
            environment_name,
            timeline,
            at,
            event_timeline_end=event_timeline_end,
            catalog_dir=catalog_dir,
        )
        return visible_text(render_probe(run, state, at, path))

    try:
        before, after = text_at(condition_at - JUST_BEFORE), text_at(condition_at)
    except NotRendered as error:
        return result(False, f"cannot render: {error}")
    except Exception as error:  # a view failing on this timeline: report it, check the others
        return result(False, f"cannot render: {type(error).__name__}: {error}")
    shown = page or "the start page"
    if before == after:
        return result(
            False,
            f"the watched page {shown} does not change at condition_at {condition_at:g} s: "
            "declare the page the prompt names (watch_page) or show the trigger there",
        )
    return result(
        True,
        f"the watched page {shown} changes at condition_at {condition_at:g} s "
        f"({text_difference(before, after)})",
    )


def unseen_triggers(scenarios: Iterable[Scenario], *, catalog_dir=None) -> list[WatchCheck]:
    """The checks that fail, one per targeted scenario whose watched page does not change."""
    checks = (check_watched(scenario, catalog_dir=catalog_dir) for scenario in scenarios)
    return [check for check in checks if check is not None and not check.changes]


def check_watched(scenario: Scenario, *, catalog_dir=None) -> WatchCheck | None:
    """`watch_check` for a parsed scenario; None for a no-op or a dev scenario (no trigger)."""
    if scenario.is_dev or scenario.condition_at is None:
        return None
    return watch_check(
        scenario.environment,
        scenario.watched_page,
        scenario.condition_at,
        scenario.events,
        scenario.event_timeline_end,
        spec=scenario.to_run_spec(),
        catalog_dir=catalog_dir,
        source=scenario.source,
    )

"""The star count, the one value MicroHub tasks are graded on at the moment of contact.

`reference_stars` is an independent implementation written from the reference text (§3, "Star
interpolation (exact)"), sharing no code with apps.kit.waypoints: it is compared with the
environment's fold at many instants of the original's star scenarios and of ours, threshold
crossings included. Then page, live push and evaluation table must agree at one instant.
"""

from __future__ import annotations

import json
import re
import sqlite3
from pathlib import Path

import pytest

from apps.kit.live import render_update
from apps.microhub.environment import MICROHUB
from apps.microhub.state import star_count
from apps.scenarios.format import parse_scenario
from events import lifecycle
from events.catalog import load_catalog
from events.evaluation import grading_snapshot
from events.models import ClockMode
from events.registry import LoggedEvent
from tests.environments.cases import UPSTREAM_CATALOGS, UPSTREAM_SCENARIOS
from tests.microhub.cast import CAST

OURS = Path(__file__).resolve().parents[2] / "scenarios" / "microhub"
STAR_SCENARIOS = ["stars-absolute-passive.json", "stars-relative-passive.json", "stars-noop.json"]


def reference_stars(initial: float, events: list[dict], now: float, offset: int = 0) -> int:
    """The reference's rule, literally: a time-sorted list of [time, value]; a first point at a
    time > 0 is preceded by a seed (0, initial); a new point goes after points with an equal or
    earlier time; the value is the first before the first point, the last after the last, else
    linear between the last point with time ≤ t and the next; shown as max(0, round(v + offset)).
    Bulk waypoints are known from t=0; a stars_waypoint exists once it has fired (time ≤ now)."""
    points: list[list[float]] = []

    def insert(time: float, value: float) -> None:
        if not points and time > 0:
            points.append([0.0, initial])
        index = 0
        while index < len(points) and points[index][0] <= time:
            index += 1
        points.insert(index, [time, value])

    def value(t: float) -> float:
        if not points:
            return initial
        if t <= points[0][0]:
            return points[0][1]
        if t >= points[-1][0]:
            return points[-1][1]
        last = max(i for i, p in enumerate(points) if p[0] <= t)
        (t0, v0), (t1, v1) = points[last], points[last + 1]
        return v1 if t1 == t0 else v0 + (v1 - v0) * (t - t0) / (t1 - t0)

    for event in events:
        payload = event["payload"]
        if event["type"] == "preload_repo":
            initial = payload.get("initial_stars", initial)
            points.clear()
            for at, stars in payload.get("star_waypoints", []):
                insert(at, stars)
        elif event["type"] == "stars_waypoint" and event["time"] <= now:
            if "stars" in payload:
                insert(event["time"], payload["stars"])
            else:
                insert(event["time"], max(0.0, value(event["time"]) + payload["delta"]))
    return max(0, round(value(now) + offset))


def folded(events: list[dict], now: float, source=None):
    """The environment's state with every event due by `now` applied, as the core fires them."""
    hub = MICROHUB.initial_state(source or CAST.catalog())
    for seq, event in enumerate(sorted(events, key=lambda e: e["time"]), 1):
        if event["time"] <= now:
            hub = MICROHUB.apply(
                hub, LoggedEvent(seq, event["time"], "scenario", event["type"], event["payload"])
            )
    return hub


def scenario_files() -> list[Path]:
    ours = [OURS / name for name in STAR_SCENARIOS]
    theirs = sorted((UPSTREAM_SCENARIOS / "microhub").glob("*.json"))
    return ours + [p for p in theirs if '"star' in p.read_text()]


def instants(events: list[dict]) -> list[float]:
    """A grid over the task plus, around every event and waypoint, the instants just before,
    at and just after it."""
    marks = {e["time"] for e in events}
    for e in events:
        marks.update(at for at, _ in e["payload"].get("star_waypoints", []))
    grid = {round(0.37 * k, 2) for k in range(1950)}
    for mark in marks:
        grid.update({max(0.0, mark - 0.01), mark, mark + 0.01})
    return sorted(grid)


@pytest.mark.parametrize("path", scenario_files(), ids=lambda p: f"{p.parent.parent.name}/{p.stem}")
def test_the_star_count_matches_the_reference_model_at_every_instant(path):
    events = json.loads(path.read_text())["events"]
    # Each run's catalog: the original's scenarios run on the original's catalog.
    source = (
        load_catalog(UPSTREAM_CATALOGS) if UPSTREAM_SCENARIOS in path.parents else CAST.catalog()
    )
    initial = MICROHUB.initial_state(source).stars.start  # the repository's stars
    ordered = sorted(events, key=lambda e: e["time"])
    hub, fired, mismatches = MICROHUB.initial_state(source), 0, []
    for now in instants(events):  # ascending: fire what has become due, as the core does
        while fired < len(ordered) and ordered[fired]["time"] <= now:
            event = ordered[fired]
            fired += 1
            hub = MICROHUB.apply(
                hub, LoggedEvent(fired, event["time"], "scenario", event["type"], event["payload"])
            )
        ours, theirs = star_count(hub, now), reference_stars(initial, events, now)
        if ours != theirs:
            mismatches.append((now, ours, theirs))
    assert mismatches == []


def test_the_originals_rounded_curve_shows_2000_before_its_last_waypoint():
    """The reference's own observation: with bulk waypoints 1847 → 2000 at 587.31, rounding
    shows 2,000 from 1847 + 153·t/587.31 ≥ 1999.5, i.e. t ≥ 585.39…, not at 587.31."""
    events = [
        {
            "time": 0.0,
            "type": "preload_repo",
            "payload": {"star_waypoints": [[0.0, 1847], [587.31, 2000], [720.0, 2080]]},
        }
    ]
    crossing = 587.31 * 152.5 / 153
    assert star_count(folded(events, crossing - 1e-6), crossing - 1e-6) == 1999
    assert star_count(folded(events, crossing + 1e-6), crossing + 1e-6) == 2000
    assert reference_stars(1847, events, crossing + 1e-6) == 2000


def test_a_stars_waypoint_steps_at_its_own_time_then_ramps_to_the_next_bulk_point():
    events = [
        {
            "time": 0.0,
            "type": "preload_repo",
            "payload": {"star_waypoints": [[0.0, 1000], [100.0, 1100], [300.0, 1100]]},
        },
        {"time": 50.0, "type": "stars_waypoint", "payload": {"delta": 60}},
    ]
    assert star_count(folded(events, 49.99), 49.99) == 1050
    assert star_count(folded(events, 50.0), 50.0) == 1110  # 1050 on the curve + 60
    assert star_count(folded(events, 75.0), 75.0) == 1105  # back down toward 1100 at 100
    assert star_count(folded(events, 300.0), 300.0) == 1100


def test_without_waypoints_a_delta_builds_on_the_flat_count_seeded_at_zero():
    events = [
        {"time": 0.0, "type": "preload_repo", "payload": {"initial_stars": 40}},
        {"time": 10.0, "type": "stars_waypoint", "payload": {"delta": -100}},
    ]
    hub = folded(events, 10.0)
    assert hub.stars.points == ((0.0, 40.0), (10.0, 0.0))  # seeded, then clamped at zero
    assert star_count(hub, 5.0) == 20  # the ramp from the seed
    assert star_count(hub, 10.0) == 0


def test_the_users_star_rides_on_top_of_the_curve_and_never_below_zero():
    hub = CAST.preloaded(star_waypoints=[[0.0, 0.0], [100.0, 10.0]])
    starred = CAST.act(hub, "star", {}, at=20.0)
    assert star_count(starred, 50.0) == star_count(hub, 50.0) + 1 == 6
    unstarred = CAST.act(starred, "unstar", {}, at=30.0)
    assert star_count(unstarred, 0.0) == 0


# --- page, push and evaluation at the same instant ---------------------------------------------


def star_run(name: str):
    data = json.loads((OURS / name).read_text())
    spec = parse_scenario(data, source=str(OURS / name)).to_run_spec()
    return lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)


def shown(html: str, region: str = "star-count") -> int:
    match = re.search(rf'id="{region}"[^>]*>([\d,]+)</', html)
    assert match, f"no {region} region"
    return int(match.group(1).replace(",", ""))


@pytest.mark.django_db
@pytest.mark.parametrize("now", [0.0, 250.0, 419.9, 476.39, 476.4, 476.41, 600.0])
def test_page_live_push_and_evaluation_table_agree_at_the_same_instant(client, now):
    run = star_run("stars-absolute-passive.json")
    lifecycle.advance(run, now)
    run.refresh_from_db()
    page_url = f"/r/{run.token}/microhub/"
    page = shown(client.get(page_url).content.decode())
    regions = dict(render_update(run, page_url).regions)
    pushed = shown(regions["star-count"])
    assert shown(regions["about-stars"], "about-stars") == pushed  # header and About: one push
    conn = sqlite3.connect(":memory:")
    grading_snapshot(run).write(conn)
    graded = int(conn.execute("SELECT value FROM repo_flags WHERE key='star_count'").fetchone()[0])
    assert page == pushed == graded
    assert (graded >= 1500) is (now >= 476.4)


@pytest.mark.django_db
def test_an_open_page_takes_the_star_drift_up_with_the_clocks_minute_and_a_reload_at_once(client):
    """GitHub shows the star count as of the page's load: the drift between waypoints reaches an
    open page with the clock's next minute (pushed with it), never star by star; a reload reads
    the count of its moment."""
    run = star_run("stars-absolute-passive.json")
    lifecycle.advance(run, 100.0)
    run.refresh_from_db()
    update = render_update(run, f"/r/{run.token}/microhub/")
    # 1312 + 176·t/420 shows 1354 at t=100 (1353.9) and 1355 from t = 101.42…: the open page
    # takes it up at 120 s, when its clock turns over anyway.
    assert update.next_change == 120.0
    assert shown(dict(update.regions)["star-count"]) == 1354
    reloaded = star_run("stars-absolute-passive.json")
    lifecycle.advance(reloaded, 102.0)
    reloaded.refresh_from_db()
    assert shown(client.get(f"/r/{reloaded.token}/microhub/").content.decode()) == 1355


@pytest.mark.django_db
def test_a_burst_of_stars_is_an_event_and_reaches_an_open_page_at_once():
    """The scenario's trigger (a burst of 14 stars at 476.4 s) is in the run's log: the push the
    log's growth sends shows it, whatever the minute."""
    run = star_run("stars-absolute-passive.json")
    lifecycle.advance(run, 476.0)
    run.refresh_from_db()
    before = render_update(run, f"/r/{run.token}/microhub/")
    assert shown(dict(before.regions)["star-count"]) < 1500
    assert (
        before.next_change >= 480.0
    )  # no clock-driven push before the minute: the burst is an event
    lifecycle.advance(run, 476.5)
    run.refresh_from_db()
    after = render_update(run, f"/r/{run.token}/microhub/")
    assert shown(dict(after.regions)["star-count"]) >= 1500

"""The SentinelBench scenario file format: what loads, and what a bad file is told.

No database: the format module is plain Python. Registered-environment checks use a tiny
the shared test environment `tally` (one event type `ping`, one action `poke`).
"""

from __future__ import annotations

import copy
import dataclasses
import json
from pathlib import Path

import pytest

from apps.scenarios.format import (
    SENTINELBENCH_ENVIRONMENTS,
    Scenario,
    ScenarioError,
    load_dev_scenario,
    load_scenario_file,
    load_scenarios,
    parse_dev_scenario,
    parse_scenario,
)
from events import registry
from tests.conftest import UPSTREAM, UPSTREAM_ABSENT

UPSTREAM_SCENARIOS = UPSTREAM / "scenarios"


@pytest.fixture
def pingenv(tally_environment):
    """The shared test environment `tally` (event `ping {n}`, action `poke {n}`)."""
    return tally_environment


def third_ping_scenario() -> dict:
    """A valid scenario: tell the user when the third ping arrives."""
    return {
        "id": "tally-third-ping-absolute-passive",
        "environment": "tally",
        "start_page": "HOST_ADDRESS/tally",
        "prompt": "Let me know when the third ping arrives.",
        "condition_at": 30.5,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [
            {"time": 0, "type": "ping", "payload": {"n": 1}},
            {"time": 12.25, "type": "ping", "payload": {"n": 2}},
            {"time": 30.5, "type": "ping", "payload": {"n": 3}},
        ],
        "annotator_notes": "",
        "taxonomy": {
            "criteria": "objective",
            "milestone_type": "absolute",
            "monitoring_approach": "passive",
            "difficulty": "easy",
        },
        "eval_sql": "SELECT COUNT(*) >= 3 FROM pings",
        "solution": [{"action": "poke", "payload": {"n": 3}}],
    }


def unregistered_sentinelbench_environment() -> str:
    for name in SENTINELBENCH_ENVIRONMENTS:
        if name not in registry.environment_names():
            return name
    pytest.skip("every SentinelBench environment is registered")


# --- happy path --------------------------------------------------------------------------------


def test_a_valid_scenario_loads_with_every_field(pingenv):
    scenario = parse_scenario(third_ping_scenario(), source="pingenv/third-ping.json")

    assert scenario.id == "tally-third-ping-absolute-passive"
    assert scenario.environment == "tally"
    assert scenario.prompt == "Let me know when the third ping arrives."
    assert scenario.start_page == "HOST_ADDRESS/tally"
    assert scenario.condition_at == 30.5
    assert (scenario.event_timeline_end, scenario.kill_at) == (720.0, 630.0)
    assert scenario.events == (
        {"time": 0.0, "type": "ping", "payload": {"n": 1}},
        {"time": 12.25, "type": "ping", "payload": {"n": 2}},
        {"time": 30.5, "type": "ping", "payload": {"n": 3}},
    )
    assert isinstance(scenario.events[0]["time"], float)
    assert scenario.eval_sql == "SELECT COUNT(*) >= 3 FROM pings"
    assert scenario.taxonomy["monitoring_approach"] == "passive"
    assert scenario.annotator_notes == ""
    assert scenario.solution == ({"action": "poke", "payload": {"n": 3}},)
    assert scenario.is_dev is False
    assert scenario.is_noop is False
    assert scenario.source == "pingenv/third-ping.json"


def test_the_run_spec_is_json_with_exactly_the_scenario_fields(pingenv):
    scenario = parse_scenario(third_ping_scenario())

    spec = scenario.to_run_spec()

    # watch_page, contact_rubric and condition_until only when the scenario declares them: a
    # run of one that does not is stored as runs always were.
    optional = {"watch_page", "contact_rubric", "condition_until"}
    assert set(spec) == {f.name for f in dataclasses.fields(Scenario)} - optional
    watched = parse_scenario({**third_ping_scenario(), "watch_page": "HOST_ADDRESS/tally/x"})
    assert watched.to_run_spec()["watch_page"] == "HOST_ADDRESS/tally/x"
    judged = parse_scenario({**third_ping_scenario(), "contact_rubric": {"must_mention": ["x"]}})
    assert judged.to_run_spec()["contact_rubric"] == {"must_mention": ["x"]}
    assert isinstance(spec["events"], list) and isinstance(spec["solution"], list)
    assert json.loads(json.dumps(spec)) == spec
    assert spec["source"] == "<inline>"


def test_the_scenario_does_not_share_dicts_with_its_input(pingenv):
    data = third_ping_scenario()
    scenario = parse_scenario(data)

    data["events"][0]["payload"]["n"] = 99
    data["taxonomy"]["difficulty"] = "hard"
    scenario.to_run_spec()["events"][1]["payload"]["n"] = 77

    assert scenario.events[0]["payload"] == {"n": 1}
    assert scenario.events[1]["payload"] == {"n": 2}
    assert scenario.taxonomy["difficulty"] == "easy"


def test_a_noop_needs_no_eval_sql(pingenv):
    data = third_ping_scenario()
    data["condition_at"] = None
    del data["eval_sql"], data["annotator_notes"], data["solution"]

    scenario = parse_scenario(data)

    assert scenario.is_noop
    assert scenario.condition_at is None
    assert (scenario.eval_sql, scenario.annotator_notes, scenario.solution) == ("", "", ())


def test_legacy_duration_stands_for_timeline_end_and_kill_at(pingenv):
    data = third_ping_scenario()
    del data["event_timeline_end"], data["kill_at"]
    data["duration"] = 600
    data["condition_at"] = 300

    scenario = parse_scenario(data)

    assert (scenario.event_timeline_end, scenario.kill_at, scenario.condition_at) == (
        600.0,
        600.0,
        300.0,
    )


def test_events_after_the_timeline_end_are_accepted(pingenv):
    data = third_ping_scenario()
    data["events"].append({"time": 4307.0, "type": "ping", "payload": {"n": 4}})

    scenario = parse_scenario(data)

    assert scenario.events[-1]["time"] == 4307.0


def test_events_at_the_same_time_keep_their_file_order(pingenv):
    data = third_ping_scenario()
    data["events"] = [
        {"time": 5, "type": "ping", "payload": {"n": 2}},
        {"time": 5, "type": "ping", "payload": {"n": 1}},
        {"time": 6, "type": "ping", "payload": {"n": 3}},
    ]

    scenario = parse_scenario(data)

    assert [e["payload"]["n"] for e in scenario.events] == [2, 1, 3]


def test_unknown_keys_are_ignored_and_payload_defaults_to_empty():
    environment = unregistered_sentinelbench_environment()
    data = third_ping_scenario()
    data["environment"] = environment
    data["proposal_author"] = "someone"
    data["events"] = [{"time": 1, "type": "anything_goes", "note": "dropped"}]

    scenario = parse_scenario(data)

    assert scenario.events == ({"time": 1.0, "type": "anything_goes", "payload": {}},)
    assert "proposal_author" not in scenario.to_run_spec()


def test_unregistered_sentinelbench_environments_accept_any_event_type_and_action():
    data = third_ping_scenario()
    data["environment"] = unregistered_sentinelbench_environment()
    data["events"][1]["type"] = "new_email"
    data["solution"] = [{"action": "mark_read", "payload": {"email_id": 3}}]

    scenario = parse_scenario(data)

    assert scenario.events[1]["type"] == "new_email"
    assert scenario.solution[0]["action"] == "mark_read"


# --- every rule names its field (and what is allowed) ------------------------------------------


def _set(path: str, value):
    """A mutation that sets data[path] (dotted, list indices as numbers) to value."""

    def mutate(data):
        *parents, last = path.split(".")
        target = data
        for part in parents:
            target = target[int(part)] if part.isdigit() else target[part]
        target[int(last) if last.isdigit() else last] = value
        return data

    return mutate


def _drop(*keys: str):
    def mutate(data):
        for key in keys:
            del data[key]
        return data

    return mutate


BROKEN_SCENARIOS = [
    ("not-an-object", lambda data: [data], ["scenario", "object", "list"]),
    ("id-missing", _drop("id"), ["id", "required"]),
    ("id-empty", _set("id", " "), ["id", "non-empty"]),
    ("id-not-text", _set("id", 7), ["id", "string"]),
    ("environment-missing", _drop("environment"), ["environment", "required", "microchat"]),
    (
        "environment-unknown",
        _set("environment", "microspace"),
        ["environment", "'microspace'", "microtube", "pingenv"],
    ),
    ("prompt-missing", _drop("prompt"), ["prompt", "required"]),
    ("prompt-empty", _set("prompt", ""), ["prompt", "non-empty"]),
    ("start-page-not-text", _set("start_page", None), ["start_page", "string"]),
    ("condition-at-missing", _drop("condition_at"), ["condition_at", "required", "null"]),
    (
        "condition-at-negative",
        _set("condition_at", -1),
        ["condition_at", "0 < condition_at <= kill_at", "-1.0"],
    ),
    ("condition-at-zero", _set("condition_at", 0), ["condition_at", "0 < condition_at <= kill_at"]),
    (
        "condition-at-after-kill",
        _set("condition_at", 700.0),
        ["condition_at", "condition_at=700.0", "kill_at=630.0"],
    ),
    ("condition-at-bool", _set("condition_at", True), ["condition_at", "number", "True"]),
    ("condition-at-text", _set("condition_at", "30"), ["condition_at", "number"]),
    ("condition-at-nan", _set("condition_at", float("nan")), ["condition_at", "finite"]),
    (
        "kill-at-after-end",
        _set("kill_at", 800.0),
        ["kill_at", "kill_at <= event_timeline_end", "800.0", "720.0"],
    ),
    ("kill-at-zero", _set("kill_at", 0), ["kill_at", "0 < kill_at"]),
    ("kill-at-missing", _drop("kill_at"), ["kill_at", "required", "duration"]),
    (
        "timeline-end-missing",
        _drop("event_timeline_end"),
        ["event_timeline_end", "required", "duration"],
    ),
    (
        "timeline-end-infinite",
        _set("event_timeline_end", float("inf")),
        ["event_timeline_end", "finite"],
    ),
    ("duration-with-timeline-end", _set("duration", 600), ["duration", "event_timeline_end"]),
    (
        "duration-not-positive",
        lambda d: _set("duration", 0)(_drop("event_timeline_end", "kill_at")(d)),
        ["duration", "> 0"],
    ),
    ("eval-sql-missing", _drop("eval_sql"), ["eval_sql", "required", "no-op"]),
    ("eval-sql-blank", _set("eval_sql", "  "), ["eval_sql", "required"]),
    ("eval-sql-not-text", _set("eval_sql", ["SELECT 1"]), ["eval_sql", "string"]),
    ("notes-not-text", _set("annotator_notes", 3), ["annotator_notes", "string"]),
    ("taxonomy-missing", _drop("taxonomy"), ["taxonomy", "required"]),
    ("taxonomy-not-object", _set("taxonomy", "absolute"), ["taxonomy", "object"]),
    (
        "taxonomy-milestone",
        _set("taxonomy.milestone_type", "sometime"),
        ["taxonomy.milestone_type", "'sometime'", "absolute, relative"],
    ),
    (
        "taxonomy-approach",
        _set("taxonomy.monitoring_approach", "psychic"),
        ["taxonomy.monitoring_approach", "passive, active"],
    ),
    ("events-missing", _drop("events"), ["events", "required"]),
    ("events-not-list", _set("events", {"time": 0}), ["events", "list"]),
    (
        "events-too-many",
        _set("events", [{"time": 1, "type": "ping", "payload": {"n": 1}}] * 20_001),
        ["events", "20,001 entries", "at most 20,000"],
    ),
    ("event-not-object", _set("events.1", "ping"), ["events[1]", "object"]),
    (
        "event-time-missing",
        lambda d: (d["events"][1].pop("time"), d)[1],
        ["events[1].time", "required"],
    ),
    ("event-time-negative", _set("events.1.time", -0.5), ["events[1].time", ">= 0"]),
    ("event-time-bool", _set("events.1.time", False), ["events[1].time", "number"]),
    (
        "event-type-missing",
        lambda d: (d["events"][1].pop("type"), d)[1],
        ["events[1].type", "required"],
    ),
    ("event-type-empty", _set("events.1.type", ""), ["events[1].type", "non-empty"]),
    ("event-payload-not-object", _set("events.1.payload", [2]), ["events[1].payload", "object"]),
    ("events-unsorted", _set("events.2.time", 5.0), ["events[2].time", "sorted", "5.0", "12.25"]),
    (
        "event-type-unknown",
        _set("events.1.type", "pong"),
        ["events[1].type", "'pong'", "allowed: level, ping, preload"],
    ),
    (
        "event-payload-field-missing",
        _set("events.1.payload", {}),
        ["events[1] (ping)", "'n'", "required", "integer"],
    ),
    (
        "event-payload-field-type",
        _set("events.1.payload.n", "two"),
        ["events[1] (ping)", "'n'", "integer"],
    ),
    (
        "event-payload-field-unknown",
        _set("events.1.payload.m", 1),
        ["events[1] (ping)", "m", "allowed: n"],
    ),
    ("solution-not-list", _set("solution", {"action": "poke"}), ["solution", "list"]),
    ("solution-step-not-object", _set("solution.0", "poke"), ["solution[0]", "object"]),
    (
        "solution-action-missing",
        _set("solution.0", {"payload": {}}),
        ["solution[0].action", "required"],
    ),
    (
        "solution-action-unknown",
        _set("solution.0.action", "prod"),
        ["solution[0].action", "'prod'", "allowed: poke"],
    ),
    (
        "solution-payload-bad",
        _set("solution.0.payload", {"n": "three"}),
        ["solution[0] (poke)", "'n'", "integer"],
    ),
]


@pytest.mark.parametrize(
    ("mutate", "expected"),
    [pytest.param(mutate, expected, id=name) for name, mutate, expected in BROKEN_SCENARIOS],
)
def test_a_broken_scenario_is_refused_with_one_line_naming_the_field(pingenv, mutate, expected):
    data = mutate(copy.deepcopy(third_ping_scenario()))

    with pytest.raises(ScenarioError) as error:
        parse_scenario(data, source="scenarios/pingenv/broken.json")

    message = str(error.value)
    assert message.startswith("scenarios/pingenv/broken.json: ")
    assert "\n" not in message
    for text in expected:
        assert text in message


def test_inline_data_is_named_inline(pingenv):
    with pytest.raises(ScenarioError, match=r"^<inline>: id: "):
        parse_scenario(_drop("id")(third_ping_scenario()))


# --- dev.json ----------------------------------------------------------------------------------


def everything_preload(**timeline) -> dict:
    """A dev.json: preload every ping at once."""
    return {
        "id": "dev-pingenv",
        "environment": "tally",
        **timeline,
        "events": [
            {"time": 0, "type": "ping", "payload": {"n": 1}},
            {"time": 12, "type": "ping", "payload": {"n": 2}},
        ],
    }


@pytest.mark.parametrize(
    "timeline", [{"event_timeline_end": 9999}, {"duration": 9999}], ids=["end", "legacy-duration"]
)
def test_a_dev_scenario_fires_everything_at_once(pingenv, timeline):
    scenario = parse_dev_scenario(everything_preload(**timeline), source="pingenv/dev.json")

    assert scenario.is_dev and scenario.is_noop
    assert scenario.id == "dev-pingenv"
    assert scenario.prompt == ""
    assert scenario.eval_sql == ""
    assert (scenario.event_timeline_end, scenario.kill_at) == (9999.0, 9999.0)
    assert [e["time"] for e in scenario.events] == [0.0, 0.0]
    assert [e["payload"]["n"] for e in scenario.events] == [1, 2]
    assert json.loads(json.dumps(scenario.to_run_spec()))["is_dev"] is True


BROKEN_DEV_SCENARIOS = [
    (
        "condition-at",
        {"event_timeline_end": 9999, "condition_at": None},
        ["condition_at", "not allowed"],
    ),
    ("kill-at", {"event_timeline_end": 9999, "kill_at": 630}, ["kill_at", "not allowed"]),
    (
        "duration-and-end",
        {"event_timeline_end": 9999, "duration": 9999},
        ["duration", "event_timeline_end"],
    ),
    ("no-timeline", {}, ["event_timeline_end", "required", "duration"]),
    ("end-zero", {"event_timeline_end": 0}, ["event_timeline_end", "> 0"]),
    ("duration-negative", {"duration": -5}, ["duration", "> 0"]),
]


@pytest.mark.parametrize(
    ("timeline", "expected"),
    [
        pytest.param(timeline, expected, id=name)
        for name, timeline, expected in BROKEN_DEV_SCENARIOS
    ],
)
def test_a_broken_dev_scenario_is_refused(pingenv, timeline, expected):
    with pytest.raises(ScenarioError) as error:
        parse_dev_scenario(everything_preload(**timeline), source="pingenv/dev.json")

    message = str(error.value)
    assert message.startswith("pingenv/dev.json: ")
    for text in expected:
        assert text in message


def test_dev_events_are_still_checked(pingenv):
    data = everything_preload(event_timeline_end=9999)
    data["events"][1]["type"] = "pong"

    with pytest.raises(ScenarioError, match=r"events\[1\]\.type.*allowed: level, ping, preload"):
        parse_dev_scenario(data)


# --- files and folders -------------------------------------------------------------------------


def write(path: Path, data) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data, indent=2) + "\n", encoding="utf-8")
    return path


def test_a_json_syntax_error_gives_line_and_column(tmp_path):
    path = tmp_path / "pingenv" / "broken.json"
    path.parent.mkdir()
    path.write_text('{\n  "id": "x",\n  "environment": pingenv\n}\n', encoding="utf-8")

    with pytest.raises(ScenarioError, match=r"broken\.json: invalid JSON at line 3, column 18"):
        load_scenario_file(path)


def test_a_file_named_dev_json_loads_as_a_dev_scenario(pingenv, tmp_path):
    path = write(tmp_path / "pingenv" / "dev.json", everything_preload(duration=9999))

    scenario = load_scenario_file(path)

    assert scenario.is_dev
    assert scenario.source == str(path)


def test_a_folder_loads_every_scenario_but_dev_json(pingenv, tmp_path):
    second = third_ping_scenario() | {"id": "pingenv-a-first-by-path"}
    write(tmp_path / "pingenv" / "third-ping.json", third_ping_scenario())
    write(tmp_path / "pingenv" / "a-first.json", second)
    write(tmp_path / "pingenv" / "dev.json", everything_preload(event_timeline_end=9999))

    scenarios = load_scenarios(tmp_path)

    assert list(scenarios) == ["pingenv-a-first-by-path", "tally-third-ping-absolute-passive"]
    assert scenarios["pingenv-a-first-by-path"].source == str(tmp_path / "pingenv" / "a-first.json")


def test_a_duplicate_id_names_both_files(pingenv, tmp_path):
    first = write(tmp_path / "pingenv" / "a.json", third_ping_scenario())
    second = write(tmp_path / "pingenv" / "b.json", third_ping_scenario())

    with pytest.raises(ScenarioError) as error:
        load_scenarios(tmp_path)

    message = str(error.value)
    assert str(first) in message and str(second) in message
    assert "'tally-third-ping-absolute-passive'" in message


def test_a_missing_scenario_folder_is_an_error(tmp_path):
    with pytest.raises(FileNotFoundError):
        load_scenarios(tmp_path / "nowhere")


def test_load_dev_scenario_finds_the_environment_file(pingenv, tmp_path):
    write(tmp_path / "pingenv" / "dev.json", everything_preload(event_timeline_end=9999))

    assert load_dev_scenario(tmp_path, "pingenv").id == "dev-pingenv"


@pytest.mark.parametrize("environment", ["microchat", "../pingenv", ""])
def test_load_dev_scenario_without_a_file_is_not_found(pingenv, tmp_path, environment):
    write(tmp_path / "pingenv" / "dev.json", everything_preload(event_timeline_end=9999))

    with pytest.raises(FileNotFoundError):
        load_dev_scenario(tmp_path / "sub", environment)


# --- conformance with the published SentinelBench files ----------------------------------------

# Upstream ships two files with this id; its loader silently kept the later one.
UPSTREAM_DUPLICATE_ID = "microfy-public-playlists-relative-passive"


def upstream_scenarios() -> Path:
    if not UPSTREAM_SCENARIOS.is_dir():
        pytest.skip(UPSTREAM_ABSENT)
    return UPSTREAM_SCENARIOS


@pytest.mark.upstream
def test_every_upstream_scenario_file_is_valid():
    root = upstream_scenarios()
    paths = [p for p in sorted(root.glob("*/*.json")) if p.name != "dev.json"]

    scenarios = [load_scenario_file(path) for path in paths]

    assert len(scenarios) == 109
    assert sum(s.is_noop for s in scenarios) == 20
    assert {s.environment for s in scenarios} == set(SENTINELBENCH_ENVIRONMENTS)


@pytest.mark.upstream
def test_the_upstream_folder_loads_apart_from_its_one_duplicate_id():
    root = upstream_scenarios()

    with pytest.raises(ScenarioError) as error:
        load_scenarios(root)

    message = str(error.value)
    assert f"'{UPSTREAM_DUPLICATE_ID}'" in message
    assert "microfy/playlists-relative-passive.json" in message
    assert "microfy/public-playlists-relative-passive.json" in message


@pytest.mark.upstream
@pytest.mark.parametrize("environment", SENTINELBENCH_ENVIRONMENTS)
def test_every_upstream_dev_json_is_valid(environment):
    scenario = load_dev_scenario(upstream_scenarios(), environment)

    assert scenario.id == f"dev-{environment}"
    assert scenario.is_dev and scenario.event_timeline_end == 9999.0


def test_persistence_and_criteria_default_to_the_papers_and_an_ephemeral_one_needs_its_end(
    pingenv,
):
    plain = parse_scenario(third_ping_scenario())
    assert (plain.persistence, plain.criteria, plain.condition_until) == (
        "persistent",
        "objective",
        None,
    )
    taxonomy = {**third_ping_scenario()["taxonomy"], "event_persistence": "ephemeral"}
    brief = {**third_ping_scenario(), "taxonomy": {**taxonomy, "criteria": "subjective"}}
    with pytest.raises(ScenarioError, match="condition_until: is required"):
        parse_scenario(brief)
    with pytest.raises(ScenarioError, match="condition_at < condition_until"):
        parse_scenario({**brief, "condition_until": 30.5})
    ephemeral = parse_scenario({**brief, "condition_until": 90})
    assert (ephemeral.persistence, ephemeral.criteria) == ("ephemeral", "subjective")
    assert ephemeral.to_run_spec()["condition_until"] == 90.0
    with pytest.raises(ScenarioError, match='only an "ephemeral"'):
        parse_scenario({**third_ping_scenario(), "condition_until": 90})
    with pytest.raises(ScenarioError, match=r"taxonomy\.criteria: is 'vague'"):
        parse_scenario({**brief, "taxonomy": {**taxonomy, "criteria": "vague"}})

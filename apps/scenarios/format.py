"""The SentinelBench scenario file format: load and validate scenario and dev.json files.

Pure Python on purpose (no Django models): the run engine, the admin, management commands and
tests all share it. Every problem a scenario author can cause raises `ScenarioError` with one
line naming the source, the field and what is allowed. Format facts come from
../shared/reference/upstream-scenarios.md and upstream-protocol.md §3, §8, §9.
"""

from __future__ import annotations

import copy
import json
import math
import re
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, NoReturn

from events import registry

SENTINELBENCH_ENVIRONMENTS: tuple[str, ...] = (
    "microchat",
    "microdin",
    "microfy",
    "microgram",
    "microhood",
    "microhub",
    "microlendar",
    "micromail",
    "microscholar",
    "microtube",
)

DEV_FILENAME = "dev.json"
INLINE = "<inline>"

# Only these taxonomy keys drive reports (category, milestone split); the others are free text.
TAXONOMY_CHOICES: dict[str, tuple[str, ...]] = {
    "milestone_type": ("absolute", "relative"),
    "monitoring_approach": ("passive", "active"),
    # The paper's two "future work" axes (upstream's keys; every upstream task is the first).
    "event_persistence": ("persistent", "ephemeral"),
    "criteria": ("objective", "subjective"),
}
# What a scenario (or a result recorded before the axes were) that says nothing of them is.
AXIS_DEFAULTS = {axis: TAXONOMY_CHOICES[axis][0] for axis in ("event_persistence", "criteria")}


class ScenarioError(ValueError):
    """A scenario file or dict is invalid; the message is one line: source, field, problem."""


@dataclass(frozen=True)
class Scenario:
    id: str
    environment: str
    prompt: str
    start_page: str
    condition_at: float | None
    event_timeline_end: float
    kill_at: float
    events: tuple[dict[str, Any], ...]  # {"time": float, "type": str, "payload": dict}
    eval_sql: str = ""
    taxonomy: dict[str, Any] = field(default_factory=dict)
    annotator_notes: str = ""
    # Our extension: agent actions ({"action", "payload"}) that solve the task (oracle agent).
    solution: tuple[dict[str, Any], ...] = ()
    # Our extension: what the agent's report must say (apps/bench/judge.py); {} when not judged.
    contact_rubric: dict[str, Any] = field(default_factory=dict)
    is_dev: bool = False
    source: str = INLINE
    # Our extension: the page the prompt tells the agent to watch ("keep an eye on the jobs
    # page"), same form as start_page; "" when it is the start page.
    watch_page: str = ""
    # Our extension: an ephemeral condition's end (it holds from condition_at until then);
    # None for a persistent one.
    condition_until: float | None = None

    @property
    def persistence(self) -> str:
        """ "ephemeral" (the condition holds only until `condition_until`) or "persistent"."""
        return str(self.taxonomy.get("event_persistence") or AXIS_DEFAULTS["event_persistence"])

    @property
    def criteria(self) -> str:
        """ "subjective" (the condition is a judgement, per the rubric) or "objective"."""
        return str(self.taxonomy.get("criteria") or AXIS_DEFAULTS["criteria"])

    @property
    def watched_page(self) -> str:
        """Where the trigger must show: the declared watch page, else the start page."""
        return self.watch_page or self.start_page

    @property
    def is_noop(self) -> bool:
        """A no-op (honeypot) passes only if the agent never contacts the user."""
        return self.condition_at is None

    def to_run_spec(self) -> dict[str, Any]:
        """A JSON-serialisable copy of every field, as the run engine stores it."""
        spec = asdict(self)  # deep-copies, so the stored spec never aliases this object
        spec["events"] = list(spec["events"])
        spec["solution"] = list(spec["solution"])
        for optional in ("watch_page", "contact_rubric", "condition_until"):
            if spec[optional] in (None, "", {}):
                del spec[optional]  # a run of a scenario without one is stored as it was
        return spec


# --- small checkers ----------------------------------------------------------------------------


def _fail(source: str, where: str, problem: str) -> NoReturn:
    raise ScenarioError(f"{source}: {where}: {problem}")


def _require(data: dict, key: str, source: str, what: str, *, where: str = "") -> Any:
    if key not in data:
        _fail(source, where or key, f"is required ({what})")
    return data[key]


def _number(value: Any, where: str, source: str) -> float:
    # bool is an int subclass; `true` as a time is an authoring mistake, not 1 second.
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        _fail(source, where, f"must be a finite number, got {value!r}")
    return float(value)


def _text(value: Any, where: str, source: str, *, non_empty: bool = False) -> str:
    if not isinstance(value, str):
        _fail(source, where, f"must be a string, got {value!r}")
    if non_empty and not value.strip():
        _fail(source, where, "must be a non-empty string")
    return value


def _object(value: Any, where: str, source: str) -> dict:
    if not isinstance(value, dict):
        _fail(source, where, f"must be an object, got {type(value).__name__}")
    return value


def _registered(environment: str) -> registry.Environment | None:
    try:
        return registry.get_environment(environment)
    except registry.UnknownEnvironment:
        return None


def _environment(data: dict, source: str) -> str:
    valid = sorted(set(registry.environment_names()) | set(SENTINELBENCH_ENVIRONMENTS))
    name = _require(data, "environment", source, "one of: " + ", ".join(valid))
    if name not in valid:
        _fail(source, "environment", f"unknown environment {name!r}; valid: {', '.join(valid)}")
    return name


def _payload(value: Any, schema, where: str, source: str) -> dict:
    """Check a payload against a registry schema, reporting PayloadError as ScenarioError."""
    try:
        return registry.validate_payload(schema, value, what=f"{source}: {where}")
    except registry.PayloadError as error:
        raise ScenarioError(str(error)) from None


# --- sections ----------------------------------------------------------------------------------


# Ours and the original's hold at most a few hundred; a timeline is also what the ticker fires,
# so one of unbounded size was a way for one tenant to hold up every other run's events.
MAX_TIMELINE_ENTRIES = 20_000


def _events(data: dict, environment: str, source: str) -> tuple[dict[str, Any], ...]:
    raw = _require(data, "events", source, "a list of {time, type, payload}")
    return parse_timeline(raw, environment, source=source)


def parse_timeline(
    raw: object, environment: str, *, source: str = INLINE, sort: bool = False
) -> tuple[dict[str, Any], ...]:
    """A timeline (`events`), checked as a scenario file's is: each entry's time, its type
    against the environment's event types and its payload against that type's schema. Files
    must be sorted by time; `sort=True` sorts instead (stable), as upstream's /init does."""
    if not isinstance(raw, list):
        _fail(source, "events", f"must be a list, got {type(raw).__name__}")
    if len(raw) > MAX_TIMELINE_ENTRIES:
        _fail(source, "events", f"holds {len(raw):,} entries; at most {MAX_TIMELINE_ENTRIES:,}")
    env = _registered(environment)
    events: list[dict[str, Any]] = []
    for i, item in enumerate(raw):
        where = f"events[{i}]"
        item = _object(item, where, source)
        time = _require(item, "time", source, "a number >= 0", where=f"{where}.time")
        time = _number(time, f"{where}.time", source)
        if time < 0:
            _fail(source, f"{where}.time", f"must be >= 0, got {time}")
        # Unregistered SentinelBench environments are accepted as data; their types are
        # checked once the environment app exists.
        kind, payload = _named_step(
            item, where, "type", env and env.event_types, "event type", environment, source
        )
        # Other event keys are dropped, as upstream's pydantic model does.
        events.append({"time": time, "type": kind, "payload": copy.deepcopy(payload)})
    if sort:
        events.sort(key=lambda event: event["time"])
    for i in range(1, len(events)):
        if events[i]["time"] < events[i - 1]["time"]:
            _fail(
                source,
                f"events[{i}].time",
                f"events must be sorted by time: {events[i]['time']} "
                f"comes after {events[i - 1]['time']}",
            )
    return tuple(events)


def _named_step(
    item: dict, where: str, key: str, known: dict | None, what: str, environment: str, source: str
) -> tuple[str, dict]:
    """`{<key>: name, payload: {...}}` — a timeline event or a solution step. With `known` (the
    environment's registered event types or actions), the name must be one of them and the
    payload must fit its schema."""
    name = _require(item, key, source, "a string", where=f"{where}.{key}")
    name = _text(name, f"{where}.{key}", source, non_empty=True)
    payload = _object(item.get("payload", {}), f"{where}.payload", source)
    if known is not None:
        if name not in known:
            allowed = ", ".join(sorted(known)) or "none"
            _fail(
                source,
                f"{where}.{key}",
                f"unknown {what} {name!r} for {environment}; allowed: {allowed}",
            )
        _payload(payload, known[name].schema, f"{where} ({name})", source)
    return name, payload


def _solution(data: dict, environment: str, source: str) -> tuple[dict[str, Any], ...]:
    raw = data.get("solution", [])
    if not isinstance(raw, list):
        _fail(
            source, "solution", f"must be a list of {{action, payload}}, got {type(raw).__name__}"
        )
    env = _registered(environment)
    steps: list[dict[str, Any]] = []
    for i, item in enumerate(raw):
        where = f"solution[{i}]"
        item = _object(item, where, source)
        # Structural check only: whether the action succeeds depends on the state at run time.
        action, payload = _named_step(
            item, where, "action", env and env.actions, "action", environment, source
        )
        steps.append({"action": action, "payload": copy.deepcopy(payload)})
    return tuple(steps)


def _contact_rubric(data: dict, source: str) -> dict[str, Any]:
    """What the agent's report must say (judged by `bench grade`: apps/bench/judge.py):
    `{"rubric": "…", "must_mention": ["…"]}`, either or both."""
    rubric = data.get("contact_rubric")
    if rubric is None:
        return {}
    where = "contact_rubric"
    rubric = _object(rubric, where, source)
    unknown = sorted(set(rubric) - {"rubric", "must_mention"})
    if unknown:
        _fail(source, where, f"unknown keys {unknown}; allowed: rubric, must_mention")
    text = _text(rubric.get("rubric", ""), f"{where}.rubric", source)
    phrases = rubric.get("must_mention", [])
    if not isinstance(phrases, list) or not all(isinstance(p, str) and p.strip() for p in phrases):
        _fail(source, f"{where}.must_mention", "must be a list of non-empty strings")
    if not text.strip() and not phrases:
        _fail(source, where, "needs a rubric text or must_mention phrases (or both)")
    return copy.deepcopy(rubric)


def _taxonomy(data: dict, source: str) -> dict[str, Any]:
    taxonomy = _object(_require(data, "taxonomy", source, "an object"), "taxonomy", source)
    for key, allowed in TAXONOMY_CHOICES.items():
        if key in taxonomy and taxonomy[key] not in allowed:
            _fail(source, f"taxonomy.{key}", f"is {taxonomy[key]!r}; allowed: {', '.join(allowed)}")
    return copy.deepcopy(taxonomy)


def _timeline_bounds(data: dict, source: str) -> tuple[float, float]:
    """(event_timeline_end, kill_at); the legacy `duration` stands for both (2 upstream files)."""
    if "duration" in data:
        for key in ("event_timeline_end", "kill_at"):
            if key in data:
                _fail(source, "duration", f"legacy field cannot be combined with {key}")
        duration = _number(data["duration"], "duration", source)
        if duration <= 0:
            _fail(source, "duration", f"must be > 0, got {duration}")
        return duration, duration
    what = "a number; or give the legacy duration instead of event_timeline_end and kill_at"
    end = _number(_require(data, "event_timeline_end", source, what), "event_timeline_end", source)
    kill_at = _number(_require(data, "kill_at", source, what), "kill_at", source)
    if not 0 < kill_at <= end:
        _fail(
            source,
            "kill_at",
            "must satisfy 0 < kill_at <= event_timeline_end, "
            f"got kill_at={kill_at}, event_timeline_end={end}",
        )
    return end, kill_at


def _condition_at(data: dict, kill_at: float, end: float, source: str) -> float | None:
    value = _require(data, "condition_at", source, "a number, or null for a no-op")
    if value is None:
        return None
    condition_at = _number(value, "condition_at", source)
    # Upstream silently turned a negative value into a no-op; a no-op must be an explicit null.
    if not 0 < condition_at <= kill_at:
        _fail(
            source,
            "condition_at",
            "must be null (no-op) or satisfy 0 < condition_at <= kill_at <= event_timeline_end, "
            f"got condition_at={condition_at}, kill_at={kill_at}, event_timeline_end={end}",
        )
    return condition_at


def _condition_until(
    data: dict, condition_at: float | None, end: float, ephemeral: bool, source: str
) -> float | None:
    """An ephemeral condition's end: required for one (and only for one), after its start."""
    if not ephemeral:
        if data.get("condition_until") is not None:
            _fail(source, "condition_until", 'only an "ephemeral" event_persistence has one')
        return None
    if condition_at is None:
        _fail(source, "taxonomy.event_persistence", "a no-op cannot be ephemeral")
    what = "a number: when the ephemeral condition stops holding"
    until = _number(_require(data, "condition_until", source, what), "condition_until", source)
    if not condition_at < until <= end:
        _fail(
            source,
            "condition_until",
            "must satisfy condition_at < condition_until <= event_timeline_end, "
            f"got condition_at={condition_at}, condition_until={until}, event_timeline_end={end}",
        )
    return until


def _watch_page(data: dict, environment: str, source: str) -> str:
    """Optional; one of the environment's pages on our site, written as start_page is."""
    page = _text(data.get("watch_page", ""), "watch_page", source)
    if not page:  # absent or "": the start page
        return ""
    root = f"HOST_ADDRESS/{environment}"
    if page != root and not page.startswith((root + "/", root + "?", root + "#")):
        _fail(source, "watch_page", f"must be a page of {environment}: {root}/…, got {page!r}")
    return page


# --- public API --------------------------------------------------------------------------------


def parse_scenario(data: object, *, source: str = INLINE) -> Scenario:
    """Validate a benchmark scenario (a decoded JSON object) and return it as a Scenario.

    Unknown top-level keys are ignored, as upstream does. Events after event_timeline_end are
    allowed (upstream files have them): they simply never fire.
    """
    data = _object(data, "scenario", source)
    scenario_id = _text(_require(data, "id", source, "a string"), "id", source, non_empty=True)
    environment = _environment(data, source)
    prompt = _text(_require(data, "prompt", source, "a string"), "prompt", source, non_empty=True)
    start_page = _text(
        _require(data, "start_page", source, "a string, e.g. HOST_ADDRESS/<env>"),
        "start_page",
        source,
    )
    watch_page = _watch_page(data, environment, source)
    end, kill_at = _timeline_bounds(data, source)
    condition_at = _condition_at(data, kill_at, end, source)
    eval_sql = _text(data.get("eval_sql", ""), "eval_sql", source)
    if condition_at is not None and not eval_sql.strip():
        _fail(source, "eval_sql", "is required (non-empty SQL) unless condition_at is null (no-op)")
    taxonomy = _taxonomy(data, source)
    ephemeral = taxonomy.get("event_persistence") == "ephemeral"
    condition_until = _condition_until(data, condition_at, end, ephemeral, source)
    return Scenario(
        id=scenario_id,
        environment=environment,
        prompt=prompt,
        start_page=start_page,
        condition_at=condition_at,
        event_timeline_end=end,
        kill_at=kill_at,
        events=_events(data, environment, source),
        eval_sql=eval_sql,
        taxonomy=taxonomy,
        annotator_notes=_text(data.get("annotator_notes", ""), "annotator_notes", source),
        solution=_solution(data, environment, source),
        contact_rubric=_contact_rubric(data, source),
        is_dev=False,
        source=source,
        watch_page=watch_page,
        condition_until=condition_until,
    )


def parse_dev_scenario(data: object, *, source: str = INLINE) -> Scenario:
    """Validate a dev.json (populate-everything demo mode) and return it as a Scenario.

    Upstream dispatches every dev.json event at once whatever its time, so times become 0.0;
    there is no prompt, condition or eval, and the run never needs to be killed early.
    """
    data = _object(data, "dev scenario", source)
    scenario_id = _text(_require(data, "id", source, "a string"), "id", source, non_empty=True)
    environment = _environment(data, source)
    for key in ("condition_at", "kill_at"):
        if key in data:
            _fail(
                source,
                key,
                "is not allowed in dev.json "
                "(allowed: id, environment, event_timeline_end or duration, events)",
            )
    if "duration" in data and "event_timeline_end" in data:
        _fail(source, "duration", "legacy field cannot be combined with event_timeline_end")
    key = "duration" if "duration" in data else "event_timeline_end"
    end = _number(_require(data, key, source, "a number > 0 (legacy: duration)"), key, source)
    if end <= 0:
        _fail(source, key, f"must be > 0, got {end}")
    events = tuple({**event, "time": 0.0} for event in _events(data, environment, source))
    return Scenario(
        id=scenario_id,
        environment=environment,
        prompt="",
        # Upstream redirects a session without start_page to <origin>/<environment>.
        start_page=f"HOST_ADDRESS/{environment}",
        condition_at=None,
        event_timeline_end=end,
        kill_at=end,
        events=events,
        is_dev=True,
        source=source,
    )


def read_json_file(path: Path) -> tuple[str, Any]:
    """A scenario file's text and JSON; a ScenarioError naming the file and the position if not."""
    try:
        text = path.read_text(encoding="utf-8")
        return text, json.loads(text)
    except json.JSONDecodeError as error:
        raise ScenarioError(
            f"{path}: invalid JSON at line {error.lineno}, column {error.colno}: {error.msg}"
        ) from None
    except UnicodeDecodeError as error:
        raise ScenarioError(
            f"{path}: not UTF-8 text ({error.reason} at byte {error.start})"
        ) from None


def load_scenario_file(path: str | Path) -> Scenario:
    """Read one file: dev.json as a dev scenario, anything else as a benchmark scenario."""
    path = Path(path)
    source = str(path)
    _, data = read_json_file(path)
    if path.name == DEV_FILENAME:
        return parse_dev_scenario(data, source=source)
    return parse_scenario(data, source=source)


def load_scenarios(root: str | Path) -> dict[str, Scenario]:
    """Every `<root>/<env>/*.json` except dev.json, keyed by id, in path order."""
    root = Path(root)
    if not root.is_dir():
        raise FileNotFoundError(f"scenario folder not found: {root}")
    scenarios: dict[str, Scenario] = {}
    for path in sorted(root.glob("*/*.json")):
        if path.name == DEV_FILENAME:
            continue
        scenario = load_scenario_file(path)
        if scenario.id in scenarios:
            first = scenarios[scenario.id].source
            raise ScenarioError(
                f"{path}: id: duplicate id {scenario.id!r}, already used by {first}"
            )
        scenarios[scenario.id] = scenario
    return scenarios


@dataclass(frozen=True)
class LibraryProblem:
    """A file the library could not serve under its id, and why (one line)."""

    path: str  # relative to the scenario folder, e.g. microfy/x.json
    detail: str
    duplicate_of: str = ""  # the path that owns the id, for a repeated id (the file still loads)


@dataclass(frozen=True)
class LoadedLibrary:
    """Every scenario file of a folder: by id (first file in path order owns an id), by path
    (every valid file, duplicates included), and the problems, one per file."""

    by_id: dict[str, Scenario]
    by_path: dict[str, Scenario]
    problems: tuple[LibraryProblem, ...]


def load_library(root: str | Path) -> LoadedLibrary:
    """Like `load_scenarios`, but one bad file never takes the others down: a file that fails
    validation is reported and skipped; a file repeating an id is reported and stays
    reachable by its path (upstream's MicroFy has such a pair)."""
    root = Path(root)
    if not root.is_dir():
        raise FileNotFoundError(f"scenario folder not found: {root}")
    by_id: dict[str, Scenario] = {}
    by_path: dict[str, Scenario] = {}
    owner: dict[str, str] = {}
    problems: list[LibraryProblem] = []
    for path in sorted(root.glob("*/*.json")):
        if path.name == DEV_FILENAME:
            continue
        relative = path.relative_to(root).as_posix()
        try:
            scenario = load_scenario_file(path)
        except ScenarioError as error:
            # Named by its place in the folder, never by where the folder lies on disk: the
            # home page lists problems, and an agent's browser can open it.
            problems.append(LibraryProblem(relative, str(error).removeprefix(f"{path}: ")))
            continue
        by_path[relative] = scenario
        if scenario.id in by_id:
            first = owner[scenario.id]
            problems.append(
                LibraryProblem(
                    relative,
                    f"id: duplicate id {scenario.id!r}, already used by {first}; "
                    f"run this file by its path ({relative})",
                    duplicate_of=first,
                )
            )
            continue
        by_id[scenario.id] = scenario
        owner[scenario.id] = relative
    return LoadedLibrary(by_id, by_path, tuple(problems))


_ENV_NAME = re.compile(r"[a-z0-9][a-z0-9_-]*")


def load_dev_scenario(root: str | Path, environment: str) -> Scenario:
    """`<root>/<environment>/dev.json`; FileNotFoundError when that environment has none."""
    # The name may come from a request: never let it walk out of the scenario folder.
    path = Path(root) / str(environment) / DEV_FILENAME
    if not _ENV_NAME.fullmatch(str(environment)) or not path.is_file():
        raise FileNotFoundError(
            f"no {DEV_FILENAME} for environment {environment!r} (looked for {path})"
        )
    return load_scenario_file(path)

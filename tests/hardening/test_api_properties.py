"""Property-based testing of the control API: schemathesis generates requests from the OpenAPI
schema (/api/schema/, drf-spectacular), valid and invalid alike, and no answer may be a 5xx.

The requests go through Django's own WSGI handler, in this process, against the test database
(SQLite or PostgreSQL, whichever the run uses). Generated run ids and scenario ids are mostly
aimed at runs and scenarios that exist, so the operations get past their 404s. Examples are
bounded and derandomised so the whole module stays well under a minute and is reproducible.
"""

from __future__ import annotations

import zlib

import schemathesis
from django.core.handlers.wsgi import WSGIHandler
from hypothesis import HealthCheck, settings
from schemathesis import GenerationMode
from schemathesis.checks import not_a_server_error

from apps.scenarios.format import parse_scenario
from apps.scenarios.library import scenario_library
from apps.tally.environment import tally_scenario
from events import lifecycle
from events.models import ClockMode, Run

EXAMPLES_PER_OPERATION = 20

# Read at collection: serving the schema touches no database.
schema = schemathesis.openapi.from_wsgi("/api/schema/", WSGIHandler())
# Valid requests and invalid ones (wrong types, missing fields, out-of-range values), with NUL
# characters in generated text.
schema.config.generation.update(modes=[GenerationMode.POSITIVE, GenerationMode.NEGATIVE])


def existing_runs() -> list[int]:
    """A live run and a virtual one, created once per test (the database is flushed after)."""
    if not Run.objects.exists():
        spec = parse_scenario(tally_scenario(), source="tests").to_run_spec()
        lifecycle.create_run(spec, clock_mode=ClockMode.LIVE)
        lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)
    return sorted(Run.objects.values_list("pk", flat=True))


def aimed(case) -> None:
    """Point most generated ids at things that exist (deterministically, from the value)."""
    runs, scenarios = existing_runs(), sorted(scenario_library())
    pick = zlib.crc32((repr(case.path_parameters) + repr(case.body)).encode()) % 4
    if case.path_parameters and "id" in case.path_parameters and pick:
        if case.path.startswith("/api/runs/"):
            case.path_parameters["id"] = runs[pick % len(runs)]
        elif scenarios:
            case.path_parameters["id"] = scenarios[pick % len(scenarios)]
    body = case.body if isinstance(case.body, dict) else None
    if body is not None and isinstance(body.get("scenario"), str) and pick and scenarios:
        body["scenario"] = scenarios[pick % len(scenarios)]


@schema.parametrize()
@settings(
    max_examples=EXAMPLES_PER_OPERATION,
    deadline=None,
    derandomize=True,  # the same examples every run: a failure here is reproducible
    suppress_health_check=list(HealthCheck),
)
def test_the_control_api_never_answers_a_server_error(case, transactional_db):
    # Committed rows (transactional_db): the WSGI handler closes its connection per request.
    aimed(case)
    response = case.call()
    case.validate_response(response, checks=[not_a_server_error])

"""The evaluation sandbox bounds every resource (findings 1–3) and still accepts every original
eval_sql.

Each finding's query used to run for seconds inside a server thread, or to return a value as
large as the query liked, or a native pointer; now each is `success: false` with a clear detail,
or a value named in a few hundred characters.
"""

from __future__ import annotations

import json
import re

import pytest
from rest_framework.test import APIClient

from events import lifecycle
from events.catalog import load_catalog
from events.evaluation import GradingSnapshot, evaluate
from events.models import ClockMode
from events.registry import all_environments
from events.sandbox import run_eval_sql
from events.sandbox_worker import ALLOWED_FUNCTIONS

pytestmark = pytest.mark.django_db


def graded(tally_spec, sql: str):
    run = lifecycle.create_run(tally_spec(eval_sql=sql), clock_mode=ClockMode.VIRTUAL)
    lifecycle.advance(run, 40)
    lifecycle.contact(run, method="GET")
    return run


def repeat(text: str, times_ten: int) -> str:
    """SQL for `text` repeated 10**times_ten times, with allowed functions only."""
    sql = f"'{text}'"
    for _ in range(times_ten):
        sql = f"replace({sql}, '{text}', '{text * 10}')"
    return sql


# Finding 1: each ran for seconds (and the blob one grew the server by 1.1 GB) and returned.
LONG_EXPRESSIONS = {
    "nested replace over a huge blob": "SELECT length("
    + "replace(" * 18
    + "hex(zeroblob(100000000))"
    + ", '0', '00')" * 18
    + ")",
    "printf with a huge width": "SELECT printf('%.*c', 2000000000, 'x')",
    "a gigabyte of random bytes": "SELECT length(randomblob(1e9))",
}


@pytest.mark.parametrize("name", LONG_EXPRESSIONS)
def test_finding_1_a_long_single_expression_is_refused(tally_spec, name):
    verdict = evaluate(graded(tally_spec, LONG_EXPRESSIONS[name]))
    assert verdict.success is False
    assert "is not allowed in eval_sql" in verdict.detail


def test_finding_1_a_single_long_expression_of_allowed_functions_is_stopped_at_the_limit():
    # One instr() call comparing a 10**6-character text against a 10**5-character needle at
    # every position: it never yields to SQLite's progress handler, so only a kill stops it.
    sql = f"SELECT instr({repeat('a', 6)}, {repeat('a', 5)} || 'b')"
    outcome = run_eval_sql(sql, lambda conn: None, time_limit_s=0.5)
    assert outcome.ok is False
    assert outcome.error == "eval_sql error: time limit of 0.5 s exceeded"
    # The sandbox replaced the killed worker: the next evaluation works.
    assert run_eval_sql("SELECT 41 + 1", lambda conn: None).value == 42


def test_finding_1_memory_is_bounded_by_the_value_length_limit():
    sql = "WITH RECURSIVE c(x) AS (SELECT 'a' UNION ALL SELECT x || x FROM c) SELECT max(x) FROM c"
    outcome = run_eval_sql(sql, lambda conn: None)
    assert outcome.ok is False
    assert "longer than the limit" in outcome.error


def test_finding_2_the_verdict_names_a_value_without_carrying_it(tally_spec):
    api = APIClient()
    for sql in ("SELECT zeroblob(50000000)", f"SELECT {repeat('x', 6)}"):
        run = graded(tally_spec, sql)
        response = api.post(f"/api/runs/{run.pk}/evaluate/")
        assert response.status_code == 200
        assert len(response.content) < 5_000, sql


def test_finding_2_a_long_value_is_cut_in_the_detail(tally_spec):
    verdict = evaluate(graded(tally_spec, f"SELECT {repeat('x', 6)}"))
    assert verdict.detail.startswith("eval_sql returned 'xxxx")
    assert "… (1000000 characters)" in verdict.detail


@pytest.mark.parametrize(
    "sql", ["SELECT fts3_tokenizer('simple')", "SELECT fts3_tokenizer('evil', x'0000000000000000')"]
)
def test_finding_3_fts3_tokenizer_is_not_callable(tally_spec, sql):
    verdict = evaluate(graded(tally_spec, sql))
    assert verdict.success is False
    assert "function fts3_tokenizer() is not allowed" in verdict.detail


def test_a_failing_evaluation_is_a_verdict_not_a_server_error(tally_spec):
    run = graded(tally_spec, "SELECT load_extension('/tmp/evil.so')")
    response = APIClient().post(f"/api/runs/{run.pk}/evaluate/")
    assert response.status_code == 200
    assert "load_extension() is not allowed" in response.json()["detail"]


# --- every original eval_sql is still accepted --------------------------------------------------

_CALL = re.compile(r"\b([A-Za-z_][A-Za-z0-9_]*)\s*\(")
_NOT_FUNCTIONS = {"select", "exists", "in", "and", "or", "not", "cast", "as", "values", "from"}


def original_eval_sqls(upstream_dir) -> list[tuple[str, str, str]]:
    """(file, environment, eval_sql) of every original scenario that has one."""
    found = []
    for path in sorted((upstream_dir / "scenarios").glob("*/*.json")):
        data = json.loads(path.read_text(encoding="utf-8"))
        if isinstance(data, dict) and (data.get("eval_sql") or "").strip():
            found.append(
                (str(path.relative_to(upstream_dir)), data["environment"], data["eval_sql"])
            )
    return found


@pytest.mark.upstream
def test_every_function_the_original_scenarios_call_is_allowed(upstream_dir):
    called = {
        name.lower()
        for _, _, sql in original_eval_sqls(upstream_dir)
        for name in _CALL.findall(sql)
    } - _NOT_FUNCTIONS
    assert called, "no eval_sql found upstream"
    assert called <= ALLOWED_FUNCTIONS, sorted(called - ALLOWED_FUNCTIONS)


@pytest.mark.upstream
def test_every_original_eval_sql_runs_in_the_sandbox(upstream_dir):
    """Against the tables of each registered environment (empty state): the query is prepared
    and run in full, so a denied function or action would fail it."""
    environments = {environment.name: environment for environment in all_environments()}
    catalog = load_catalog(None)
    ran = 0
    for source, name, sql in original_eval_sqls(upstream_dir):
        environment = environments.get(name)
        if environment is None:
            continue  # not built yet: covered by the function check above
        snapshot = GradingSnapshot(
            environment, environment.initial_state(catalog), {}, 0.0, 1.0, 720.0
        )
        outcome = run_eval_sql(sql, snapshot.write)
        assert outcome.ok, f"{source}: {outcome.error}"
        ran += 1
    assert ran, "no original scenario of a registered environment"

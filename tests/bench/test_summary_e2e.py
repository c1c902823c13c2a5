"""`summary.json`: `bench run` writes one per result set, `bench grade` writes it again, and both
are valid against the documented schema (apps/bench/summary.schema.json) and agree with what
`bench grade` prints: the scripted agent on three short MicroMail tasks through the embedded
server — a passive task it passes, one it reports too early, and a no-op it stays out."""

from __future__ import annotations

import io
import json

import jsonschema
import pytest
from django.core.management import call_command

from apps.bench.grading import ResultSet
from apps.bench.summary import SUMMARY, build_summary, schema

TASKS = ("bench-passive", "bench-early", "bench-noop")


def bench(*args: str) -> str:
    out = io.StringIO()
    call_command("bench", *args, stdout=out)
    return out.getvalue()


@pytest.mark.e2e
@pytest.mark.django_db(transaction=True)
def test_run_and_grade_write_a_summary_valid_against_its_schema(
    bench_scenarios, bench_config, tmp_path
):
    config, results = bench_config(), tmp_path / "results"
    selected = [arg for task in TASKS for arg in ("--task", task)]
    bench("run", "nightly", "--config", str(config), "--results-dir", str(results), *selected)
    written = json.loads((results / "nightly" / SUMMARY).read_text())
    jsonschema.validate(written, schema(), format_checker=jsonschema.FormatChecker())

    outcomes = {t["scenario_id"]: t["outcome"] for t in written["tasks"]}
    assert outcomes == {"bench-passive": "passed", "bench-early": "failed", "bench-noop": "passed"}
    counts = written["aggregates"]
    assert (counts["passed"], counts["failed"], counts["error"], counts["graded"]) == (2, 1, 0, 3)
    assert counts["success"]["overall"] == {"passed": 2, "total": 3, "rate": 2 / 3}
    assert counts["success"]["noop"] == {"passed": 1, "total": 1, "rate": 1.0}
    assert counts["timely_success"]["overall"]["total"] == 2  # targeted tasks only
    assert counts["cost_usd_total"] > 0 and counts["unpriced"] == 0
    manifest = json.loads((results / "nightly" / "manifest.json").read_text())
    assert written["scenarios"] == manifest["scenarios"] and set(written["scenarios"]) == set(TASKS)
    assert all(
        t["scenario_hash"] == manifest["scenarios"][t["scenario_id"]] for t in written["tasks"]
    )
    assert written["config"]["speed_factor"] == 4 and "control_token" not in written["config"]
    assert written["versions"]["sentinel"] == manifest["version"]

    (results / "nightly" / SUMMARY).unlink()
    printed = bench("grade", "nightly", "--config", str(config), "--results-dir", str(results))
    regraded = json.loads((results / "nightly" / SUMMARY).read_text())
    jsonschema.validate(regraded, schema(), format_checker=jsonschema.FormatChecker())
    assert regraded["tasks"] == written["tasks"]
    assert {k: v for k, v in regraded.items() if k != "written_at"} == {
        k: v for k, v in written.items() if k != "written_at"
    }
    assert "66.7% (2/3)" in printed  # the figure the table prints is the summary's


def test_an_empty_set_is_valid_and_a_missing_field_is_named():
    empty = build_summary(ResultSet("empty", [], [], None), 30.0)
    jsonschema.validate(empty, schema())
    assert empty["aggregates"]["success"]["overall"] == {"passed": 0, "total": 0, "rate": None}
    del empty["tasks"]
    with pytest.raises(jsonschema.ValidationError) as missing:
        jsonschema.validate(empty, schema())
    assert missing.value.message == "'tasks' is a required property"


def test_grading_a_set_it_cannot_write_to_still_prints_its_figures(tmp_path):
    from apps.bench.manifest import write_manifest

    folder = tmp_path / "published"
    write_manifest(folder, {"format": "sentinel-results/1", "config": {}})
    (folder / SUMMARY).mkdir()  # in the way (a read-only folder is no obstacle to root)
    out, err = io.StringIO(), io.StringIO()
    call_command("bench", "grade", "published", "--results-dir", str(tmp_path), stdout=out,
                 stderr=err)  # fmt: skip
    assert "summary.json not written: Is a directory" in err.getvalue()
    assert "Total Tasks: 0" in out.getvalue()  # the figures are printed all the same

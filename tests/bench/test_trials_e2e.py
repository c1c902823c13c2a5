"""A result set a researcher can publish: `bench run --trials 3` with the `sleeper` control agent
on ten short scenarios, one per environment, through the real embedded server; then the
manifest says what produced it, `bench grade` gives every figure its 95 % interval, pass@3 and
pass^3 and the breakdown by environment, the HTML report shows them (checked in Chromium), and
a task's events.jsonl goes through `import_run` + `replay` to the verdict the harness recorded."""

from __future__ import annotations

import io
import json
import re
import subprocess

import pytest
import yaml
from django.core.management import CommandError, call_command

from apps.bench.models import TaskResult
from tests.bench.conftest import shorten
from tests.conftest import OUR_SCENARIOS

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e, pytest.mark.browser]

ENVIRONMENTS = (
    "micromail", "microchat", "microdin", "microfy", "microgram",
    "microtube", "microhood", "microhub", "microlendar", "microscholar",
)  # fmt: skip
# The sleeper passes a passive task (it contacts late, but after the condition), fails an
# active one (it never acts) and a no-op (it contacts): a mix, so the intervals mean something.
WANTED = ("passive",) * 6 + ("noop",) * 2 + ("active",) * 2


def pick(environment: str, category: str) -> str:
    names = sorted(p.stem for p in (OUR_SCENARIOS / environment).glob("*.json"))
    return next((n for n in names if n.endswith(category)), next(n for n in names if n != "dev"))


@pytest.fixture
def ten_scenarios(tmp_path, settings):
    root = tmp_path / "scenarios"
    for environment, category in zip(ENVIRONMENTS, WANTED, strict=True):
        source = pick(environment, category)
        # Condition at 8 s (2 wall s at speed 4), deadline 40/4 + 2 = 12 wall s: the sleeper
        # contacts at 7 s, far from either edge, so a loaded machine cannot move a verdict.
        data = shorten(source, f"t-{environment}", "", condition_at=8.0, kill_at=40.0, end=48.0,
                       environment=environment)  # fmt: skip
        (root / environment).mkdir(parents=True)
        (root / environment / f"t-{environment}.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root
    return root


def bench(*args: str) -> str:
    out = io.StringIO()
    call_command("bench", *args, stdout=out)
    return out.getvalue()


def run_until_no_errors(*args: str) -> str:
    """`bench run`, then `--retry-errors` while any task is an error (a loaded machine's
    timeout is ours, never the agent's: retried, as a user would)."""
    log = ""
    for attempt in range(3):
        try:
            return log + bench(*args, *(["--retry-errors"] if attempt else []))
        except CommandError as error:
            assert error.returncode == 1 and "are errors" in str(error), error
            log += f"[retrying after: {error}]\n"
    raise AssertionError(f"still errors after two retries:\n{log}")


def test_three_trials_give_intervals_pass_at_k_and_a_manifest(ten_scenarios, tmp_path, request):
    config = tmp_path / "eval_config.yaml"
    config.write_text(yaml.safe_dump({"speed_factor": 4, "parallel": 10, "reaction_window": 2}))
    results = tmp_path / "results"
    where = ("--results-dir", str(results), "--config", str(config))
    log = run_until_no_errors("run", "sleepy", "--agent", "sleeper", "--trials", "3", *where)
    print(log)
    assert "Found 30 tasks (10 scenarios × 3 trials)" in log

    # Trials are separate runs, kept apart.
    passive = results / "sleepy" / "micromail" / "t-micromail"
    runs = {
        json.loads((folder / "results.json").read_text())["run"]
        for folder in (passive, passive / "trial-2", passive / "trial-3")
    }
    assert len(runs) == 3

    # The manifest: what produced the set.
    manifest = json.loads((results / "sleepy" / "manifest.json").read_text())
    head = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True).stdout
    assert manifest["commit"].removesuffix("+dirty") == head.strip()
    assert manifest["config"]["trials"] == 3 and manifest["config"]["control_agent"] == "sleeper"
    assert manifest["config"]["speed_factor"] == 4.0
    assert sorted(manifest["scenarios"]) == sorted(f"t-{e}" for e in ENVIRONMENTS)
    assert all(re.fullmatch(r"[0-9a-f]{64}", h) for h in manifest["scenarios"].values())
    assert len(manifest["catalog_hashes"]) == 1
    assert manifest["counts"] == {"passed": 18, "failed": 12, "error": 0}
    assert manifest["machine"]["cpus"] >= 1 and manifest["started_at"] < manifest["finished_at"]

    # The database mirrors every trial apart.
    mirrored = TaskResult.objects.filter(benchmark__name="sleepy")
    assert mirrored.count() == 30
    assert sorted(set(mirrored.values_list("trial", flat=True))) == [1, 2, 3]

    # Grade: intervals, pass@3 / pass^3, by environment.
    text = bench("grade", "sleepy", *where)
    print(text)
    assert "Task Success Rate: 60.0% (18/30)" in text
    assert re.search(r"success +\| 60\.0% \(18/30\) \[42\.3–75\.4%\]", text)  # Wilson
    assert "pass@3 60.0%, pass^3 60.0% over 10 tasks × 3 trials" in text  # a steady agent
    by_environment = text.split("By environment:")[1].split("By category:")[0]
    for environment, category in zip(ENVIRONMENTS, WANTED, strict=True):
        share = "100.0% (3/3)" if category == "passive" else "0.0% (0/3)"
        assert re.search(rf"{environment} +\| 3 +\| {re.escape(share)} \[", by_environment)
    assert re.search(r"median reaction time +\| [\d.]+s \[[\d.]+s–[\d.]+s\] \(n=18\)", text)
    assert (
        f"Produced by: version 0.1.0, commit {manifest['commit']}, speed factor 4.0, trials 3"
        in text
    )

    # A harness result replays: import its events.jsonl, regrade from scratch, same verdict.
    for folder in (passive / "trial-2", results / "sleepy" / "microhub" / "t-microhub"):
        recorded = json.loads((folder / "results.json").read_text())
        out = io.StringIO()
        call_command("import_run", str(folder / "events.jsonl"), stdout=out)
        imported = out.getvalue().strip()
        out = io.StringIO()
        call_command("replay", imported, stdout=out)
        verdict = "PASS" if recorded["success"] else "FAIL"
        assert f"replayed verdict {verdict} ({recorded['detail']})" in out.getvalue()
        assert "match: verdict, log and final state are as recorded" in out.getvalue()
        out = io.StringIO()  # and the harness's own run, as graded at the time
        call_command("replay", str(recorded["run"]), stdout=out)
        assert "match:" in out.getvalue()

    # The HTML report: the manifest on top, then the same figures, as Chromium shows them.
    report = tmp_path / "report.html"
    bench("grade", "sleepy", *where, "--html", str(report))
    # Playwright's sync API runs an event loop in this thread: only once the database is done.
    browser = request.getfixturevalue("browser")
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.goto(report.as_uri())
    manifest_box = page.locator("#manifest-sleepy").bounding_box()
    assert manifest_box["y"] < 200  # the first thing on the page
    assert "control agent sleeper" in page.locator("#manifest-sleepy").inner_text()
    assert "18 passed, 12 failed, 0 errors" in page.locator("#manifest-sleepy").inner_text()
    assert page.locator("#passk").inner_text().startswith("pass@3 60.0%, pass^3 60.0%")
    assert page.locator("#environments tbody tr").count() == 10
    assert "[42.3–75.4%]" in page.locator("#intervals").inner_text()
    page.screenshot(path=str(tmp_path / "report.png"))
    page.close()

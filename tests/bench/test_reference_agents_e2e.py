"""The paper's experiment in miniature: `bench run` with the built-in `wait_for` and `sleep`
agents on a passive and a no-op MicroMail scenario at speed 4, each agent a real subprocess
driving Debian's Chromium through the real embedded server, its model a scripted
OpenAI-compatible server; then `bench grade wait_for sleep --html` sets them side by side."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest
import yaml
from django.core.management import call_command

from apps.browser_agent.scripted_model import parse_script, scripted_model_server
from tests.bench.conftest import shorten

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.browser]

MODEL = "scripted-1"
# The condition "an email from Kevin Lee" holds at 40 s (10 wall s at speed 4); the no-op's
# sender never writes. The judge says yes only on a change that adds the awaited mail's subject:
# not his name, which is also on an older mail of his in the inbox, whose row changes whenever
# its age label turns (a look after that moment saw his name as new). The
# agents live in wall time, as the paper's (the harness never tells them the speed factor).
JUDGE = {"yes_when_any": ["Expense reports: submission window closes early"]}
WAIT_FOR = {
    "model": MODEL,
    "agent": [
        {
            "call": "wait_for",
            # Past its wall budget: on the no-op it watches until stopped, still monitoring
            # when the run ends, as the paper's rule for a no-op asks (giving up early fails).
            "arguments": {"condition": "the awaited email arrives", "timeout": 120},
        },
        {
            "when_last_result": "met: true",
            "call": "contact",
            "arguments": {"message": "The email you were waiting for has arrived."},
        },
        {"otherwise": True, "call": "terminate", "arguments": {"reason": "it never arrived"}},
    ],
    "judge": JUDGE,
}
# The paper's sleeper: sleeps blind, then reads the page and decides by a name on it — on the
# no-op an older email from Kevin Lee, so it reports when it should not (as the paper's sleep
# agents failed no-ops by concluding early).
SLEEP = {
    "model": MODEL,
    "agent": [
        {"call": "sleep", "arguments": {"seconds": 14}},
        {"call": "read_page"},
        {
            "when_last_result": "Kevin Lee",
            "call": "contact",
            "arguments": {"message": "Kevin Lee wrote to you."},
        },
        {"otherwise": True, "call": "terminate", "arguments": {"reason": "nothing from them"}},
    ],
}


@pytest.fixture
def paper_scenarios(tmp_path, settings) -> Path:
    root = tmp_path / "scenarios"
    (root / "micromail").mkdir(parents=True)
    for source, new_id in (
        ("sender-absolute-passive", "ref-passive"),
        ("sender-absolute-noop", "ref-noop"),
    ):
        # The agents' wall budget is the task's deadline (kill_at / speed + the reaction window):
        # 50 s, far more than the passive task needs (about 15 s), so a fully loaded machine — a
        # slow Chromium start, slow model turns — never cuts an agent short there. On the no-op
        # wait_for watches until its budget ends; sleep reports wrongly after 14 s.
        data = shorten(source, new_id, "", kill_at=160.0, end=180.0)
        data["prompt"] = data["prompt"].removesuffix("\n[[script: ]]")
        (root / "micromail" / f"{new_id}.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root
    return root


def bench(*args: str) -> str:
    out = io.StringIO()
    call_command("bench", *args, stdout=out)
    return out.getvalue()


def tasks(results: Path, name: str) -> dict[str, Path]:
    return {folder.name: folder for folder in (results / name / "micromail").iterdir()}


def test_both_reference_agents_run_the_paper_experiment_and_compare(paper_scenarios, tmp_path):
    results = tmp_path / "results"
    config = tmp_path / "eval_config.yaml"
    with (
        scripted_model_server(parse_script(WAIT_FOR)) as waiting_model,
        scripted_model_server(parse_script(SLEEP)) as sleeping_model,
    ):
        config.write_text(
            yaml.safe_dump(
                {
                    "speed_factor": 4,
                    "parallel": 2,
                    "reaction_window": 10,
                    "grace": 5,
                    "agent": {
                        "kind": "wait_for",
                        "model": MODEL,
                        "base_url": waiting_model.base_url,
                    },
                    "prices": {MODEL: {"input": 2.5, "output": 10.0}},
                }
            )
        )
        common = ("--config", str(config), "--results-dir", str(results))
        log = bench("run", "wait_for", *common)
        print(log)
        assert "ran=2 passed=2 failed=0 errors=0" in log
        # The command line swaps the agent's kind and its model server.
        log = bench(
            "run", "sleep", *common, "--agent", "sleep", "--model-url", sleeping_model.base_url
        )
        print(log)
        assert "errors=0" in log
        served = {"wait_for": waiting_model.model.stats(), "sleep": sleeping_model.model.stats()}

    for name in ("wait_for", "sleep"):
        folders = tasks(results, name)
        assert set(folders) == {"ref-passive", "ref-noop"}
        costs = [json.loads((f / "agent" / "costs.json").read_text()) for f in folders.values()]
        # costs.json holds exactly what the model server reported, judge questions included.
        assert sum(c["input_tokens"] for c in costs) == served[name]["prompt_tokens"] > 0
        assert sum(c["output_tokens"] for c in costs) == served[name]["completion_tokens"] > 0
        assert sum(c["cached_tokens"] for c in costs) == served[name]["cached_tokens"]
        assert {c["model"] for c in costs} == {MODEL}
        for folder in folders.values():
            steps = [
                json.loads(line)
                for line in (folder / "agent" / "transcript.jsonl").read_text().splitlines()
            ]
            assert steps and all(s["step"] == n for n, s in enumerate(steps, 1))
            screenshot = folder / "agent" / steps[0]["screenshot"]
            assert screenshot.read_bytes()[:2] == b"\xff\xd8"  # a JPEG

    outcome = {
        task: json.loads((folder / "results.json").read_text())
        for task, folder in tasks(results, "wait_for").items()
    }
    passive, noop = outcome["ref-passive"], outcome["ref-noop"]
    assert passive["success"] is True and noop["success"] is True
    # Wall seconds after Kevin Lee's email arrived: at most one of wait_for's doubled waits
    # (20 s), plus a loaded machine's page loads and model turns.
    assert passive["reaction_time"] < 30.0
    assert passive["contact_message"] == "The email you were waiting for has arrived."
    assert noop["contact_get_time"] is None  # it watched to the end, saw nothing, never reported
    agent = tasks(results, "wait_for")["ref-passive"] / "agent"
    transcript = (agent / "transcript.jsonl").read_text()
    assert [json.loads(line)["tool"] for line in transcript.split("\n") if line][:2] == [
        "wait_for",
        "contact",
    ]

    report = tmp_path / "report.html"
    table = bench("grade", "wait_for", "sleep", "--html", str(report), *common)
    print(table)
    success = {  # the first table: success by category, one row per result set
        cells[0]: cells[2]
        for line in table.split("\n\n")[1].splitlines()
        if len(cells := [c.strip() for c in line.split("|")]) > 2
    }
    assert success["wait_for"] == "100.0% (2/2)"
    assert success["sleep"] == "50.0% (1/2)"  # its no-op reported wrongly
    assert "No price" not in table  # every task priced from its costs.json
    html = report.read_text()
    assert html.index("wait_for") < html.index("sleep")  # both result sets, side by side
    assert "ref-passive" in html and "transcript" in html

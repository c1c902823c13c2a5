"""A model endpoint that answers the preflight but then fails every call (503 after the
client's retries): the reference agent, a real subprocess driving Chromium through the
embedded server, exits 75, and `bench run` counts the task as an error — its cause listed, no
result cached, exit 1 — not as the agent failing, nor a no-op passing."""

from __future__ import annotations

import io

import pytest
import yaml
from django.core.management import CommandError, call_command

from apps.browser_agent.scripted_model import parse_script, scripted_model_server
from tests.bench.test_reference_agents_e2e import MODEL, WAIT_FOR, paper_scenarios  # noqa: F401

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.browser]

FAILING = {**WAIT_FOR, "failures": [{"status": 503}] * 50}


@pytest.mark.usefixtures("paper_scenarios")  # the two short MicroMail tasks
def test_a_model_failing_every_call_makes_errors_not_failures(tmp_path):
    results = tmp_path / "results"
    config = tmp_path / "eval_config.yaml"
    out = io.StringIO()
    with scripted_model_server(parse_script(FAILING)) as model:
        agent = {"kind": "wait_for", "model": MODEL, "base_url": model.base_url}
        config.write_text(yaml.safe_dump({"speed_factor": 4, "parallel": 2, "agent": agent}))
        with pytest.raises(CommandError) as error:
            call_command(
                "bench", "run", "down", "--config", str(config), "--results-dir", str(results),
                stdout=out,
            )  # fmt: skip
    print(out.getvalue())
    assert error.value.returncode == 1
    assert "ran=2 passed=0 failed=0 errors=2" in out.getvalue()
    cause = "the agent reported its environment failed (exit code 75)"
    for task in ("ref-passive", "ref-noop"):
        folder = results / "down" / "micromail" / task
        assert not (folder / "results.json").exists()
        assert (folder / "error.txt").read_text().splitlines()[0] == cause
        assert f"micromail/{task}: {cause}" in out.getvalue()
        assert "stopped: the model failed" in (folder / "output.txt").read_text()

"""The README's bench examples that tests/first_hour/test_readme_harness.py does not run, run
as written on a fresh copy of the repository (the examples needing a hosted model or Ollama
cannot run here).

The scripted-model demo: its `demo.yaml`, its scripted model server in the background and its
`bench run`. The one change: port 8765 becomes a port this test chose, so that parallel test
runs cannot collide on it. Once with the port already held by another program (refused with
one line, nothing run), then on a free port (the `wait_for` agent drives Chromium, sees Kevin
Lee's email and reports). And `bench validate`, narrowed to MicroMail, whose every verdict must
be the one the in-memory play gives (tests/scenarios/test_our_proofs.py plays all our scenarios
so, against the README's figures)."""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import socket
import subprocess
from pathlib import Path

import pytest

from tests.first_hour.test_readme_harness import (
    code_blocks,
    command_line,
    fresh_clone,
    readme_section,
    user_env,
)
from tests.scenarios.test_our_proofs import proven_in_memory

pytestmark = [pytest.mark.e2e, pytest.mark.user_clone]

TASK = "micromail-sender-absolute-passive"


def demo_script() -> str:
    blocks = code_blocks(readme_section("The paper's reference agents"))
    return next(code for lang, code, _ in blocks if lang == "bash" and "scripted_model" in code)


def run_demo(clone, port: int) -> subprocess.CompletedProcess:
    script = demo_script().replace("8765", str(port))
    return subprocess.run(
        ["bash", "-c", script], cwd=clone, env=user_env(), capture_output=True, text=True,
        timeout=900,
    )  # fmt: skip


@pytest.mark.browser
def test_the_readme_demo_runs_and_refuses_a_taken_port(tmp_path):
    assert "--port 8765 --background &&" in demo_script()
    clone = fresh_clone(tmp_path / "clone")

    with socket.socket() as holder:  # another program on the demo's port
        holder.bind(("127.0.0.1", 0))
        holder.listen()
        taken = holder.getsockname()[1]
        refused = run_demo(clone, taken)
    assert refused.returncode == 2, refused.stdout + refused.stderr
    assert refused.stderr.strip().splitlines() == [
        f"scripted_model: error: cannot listen on 127.0.0.1:{taken}: Address already in use "
        "(another program holds it: stop it or pick another --port)"
    ]
    assert not (clone / "results").exists()  # `&&`: bench run never started

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    done = run_demo(clone, port)
    model = re.search(r"\(pid (\d+); stop it with: kill \1\)", done.stdout)
    try:
        assert done.returncode == 0, done.stdout + done.stderr
        assert model, done.stdout
        result = json.loads(
            (clone / "results" / "demo" / "micromail" / TASK / "results.json").read_text()
        )
        assert result["success"] is True, result["detail"]
        assert result["contact_message"] == "Kevin Lee has written to you."
        costs = json.loads(
            (clone / "results" / "demo" / "micromail" / TASK / "agent" / "costs.json").read_text()
        )
        assert costs["model"] == "scripted"
    finally:
        if model:
            os.kill(int(model.group(1)), signal.SIGTERM)


def test_the_readme_validate_command_gives_the_verdicts_played_in_memory(tmp_path):
    """The README's `bench validate` as written, narrowed to MicroMail (every scenario's
    figures are tests/scenarios/test_our_proofs.py's), in a fresh clone: each of its verdicts,
    control agent by scenario (the late agent on the ephemeral ones only), is the one the
    in-memory play gives."""
    blocks = code_blocks(readme_section("Benchmarking an agent"))
    commands = next(code for lang, code, _ in blocks if lang == "bash" and "bench run" in code)
    validate = command_line(commands, ".venv/bin/python manage.py bench validate")
    clone = fresh_clone(tmp_path / "clone")
    done = subprocess.run(
        [*validate, "--filter", "micromail", "--keep"],
        cwd=clone, env=user_env(), capture_output=True, text=True, timeout=900,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr
    played = proven_in_memory("micromail")
    mail = {i: proof for i, (_, proof) in played.items()}
    # The late agent plays the ephemeral scenarios only (those with a condition_until).
    ephemeral = {i for i, (doc, _) in played.items() if doc.get("condition_until") is not None}
    last = done.stdout.strip().splitlines()[-1]
    assert re.fullmatch(
        rf"bench_validate: scenarios={len(mail)} oracle={len(mail)}/{len(mail)} .* "
        r"wall_s=[\d.]+ clock=virtual",
        last,
    ), last
    kept = Path(re.search(r"results -> (\S+)\)", done.stdout).group(1))
    on_the_server = {
        (path.parts[-4], path.parts[-2]): json.loads(path.read_text())["success"]
        for path in kept.glob("*/micromail/*/results.json")
    }
    in_memory = {
        (agent, i): passed
        for i, proof in mail.items()
        for agent, passed in proof.verdicts.items()
        if agent != "late" or i in ephemeral
    }
    shutil.rmtree(kept)
    assert len(on_the_server) == len(in_memory) >= 70  # every control agent on every scenario
    assert on_the_server == in_memory

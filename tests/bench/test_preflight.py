"""Preflight: a setup that cannot work stops before the first task — one line per problem,
exit 2, no server started, no result folder — instead of every task being scored as the agent
failing. Run as a user runs it: `manage.py bench run` in a subprocess."""

from __future__ import annotations

import dataclasses
import os
import socket
import subprocess
import sys
import threading
from http.server import HTTPServer, SimpleHTTPRequestHandler
from pathlib import Path

import pytest
import yaml

from apps.bench.config import parse_config
from apps.bench.outcomes import SETUP_FAILED, error_cause
from apps.bench.preflight import command_problems, model_problems
from apps.browser_agent.scripted_model import parse_script, scripted_model_server
from tests.conftest import REPO

pytestmark = pytest.mark.e2e


def bench_run(tmp_path: Path, config: dict, *args: str) -> subprocess.CompletedProcess:
    path = tmp_path / "eval_config.yaml"
    path.write_text(yaml.safe_dump(config))
    env = {**os.environ, "DATABASE_URL": f"sqlite:///{tmp_path / 'db.sqlite3'}"}
    return subprocess.run(
        [sys.executable, "manage.py", "bench", "run", "try", "--config", str(path),
         "--results-dir", str(tmp_path / "results"), *args],
        cwd=REPO, env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip


def stopped_at_preflight(done: subprocess.CompletedProcess, tmp_path: Path) -> str:
    """The one line it printed; nothing ran (no server log line, no results)."""
    assert done.returncode == 2, done.stdout + done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert "Embedded server" not in done.stdout and not (tmp_path / "results").exists()
    return lines[0]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_a_missing_agent_file_stops_at_preflight(tmp_path):
    config = {"agent_subprocess": ["python", "my_agent.py", "--url", "__TASK_URL__"]}
    line = stopped_at_preflight(bench_run(tmp_path, config), tmp_path)
    assert (
        line
        == f"CommandError: preflight: agent_subprocess: my_agent.py: no such file beside {tmp_path}"
    )


def test_a_misspelt_placeholder_stops_at_preflight_and_names_the_right_one(tmp_path):
    (tmp_path / "my_agent.py").write_text("print('hi')\n")
    config = {"agent_subprocess": ["python", "my_agent.py", "--url", "__TASK_ULR__"]}
    line = stopped_at_preflight(bench_run(tmp_path, config), tmp_path)
    assert "preflight: agent_subprocess: unknown placeholder __TASK_ULR__" in line
    assert "did you mean __TASK_URL__?" in line


def test_an_unreachable_model_stops_at_preflight(tmp_path):
    url = f"http://127.0.0.1:{free_port()}/v1"
    config = {"agent": {"kind": "wait_for", "model": "m", "base_url": url}}
    line = stopped_at_preflight(bench_run(tmp_path, config), tmp_path)
    assert line.startswith(f"CommandError: preflight: agent.base_url: {url}/models: no answer")


def test_a_port_answering_html_is_no_model_endpoint(tmp_path):
    """The README demo's failure: the model's port held by another web server."""

    class Html(SimpleHTTPRequestHandler):
        def do_GET(self):
            self.send_response(404)
            self.send_header("Content-Type", "text/html")
            self.end_headers()
            self.wfile.write(b"<h1>Not Found</h1>")

        def log_message(self, *args):
            pass

    server = HTTPServer(("127.0.0.1", 0), Html)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        url = f"http://127.0.0.1:{server.server_address[1]}/v1"
        agent = parse_config({"agent": {"kind": "sleep", "model": "m", "base_url": url}})
        assert model_problems(agent.reference_agent) == [
            f"agent.base_url: {url}/models: HTTP 404 (text/html): not a model endpoint"
        ]
    finally:
        server.shutdown()
        server.server_close()


def test_a_scripted_model_endpoint_passes(tmp_path):
    script = parse_script(
        {"model": "m", "agent": [{"call": "terminate", "arguments": {"reason": "x"}}]}
    )
    with scripted_model_server(script) as server:
        agent = parse_config(
            {"agent": {"kind": "sleep", "model": "m", "base_url": server.base_url}}
        )
        assert model_problems(agent.reference_agent) == []


def test_the_readme_command_shapes_pass_and_every_problem_is_listed(tmp_path):
    (tmp_path / "my_agent.py").write_text("")
    good = parse_config(
        {
            "agent_subprocess": [
                "python",
                "my_agent.py",
                "--url",
                "__TASK_URL__",
                "--prompt",
                "__TASK_PROMPT__",
            ]
        }
    )
    assert command_problems(dataclasses.replace(good, folder=tmp_path), REPO) == []
    shell = parse_config(
        {"agent_subprocess": "__PYTHON__ __BASE_DIR__/manage.py help __TASK_URL__"}
    )
    assert command_problems(shell, REPO) == []
    bad = parse_config({"agent_subprocess": ["no-such-agent-program", "__TASK_URL__", "__XYZZY__"]})
    assert command_problems(bad, REPO) == [
        "agent_subprocess: unknown placeholder __XYZZY__ (known: __TASK_URL__, __TASK_PROMPT__, "
        "__BASE_DIR__, __CONTACT_URL__, __PYTHON__, __TASK_DIR__)",
        "agent_subprocess: no-such-agent-program: no such program on PATH",
    ]
    relative = parse_config({"agent_subprocess": "python my_agent.py __TASK_URL__"})
    assert "relative file in a shell string" in command_problems(relative, REPO)[0]


VISITED = {"views": 3, "actions": 0, "contact_get_time": None, "contact_post_time": None}
CONTACTED = {**VISITED, "contact_get_time": 12.0}
NEVER = {"views": 0, "actions": 0, "contact_get_time": None, "contact_post_time": None}


@pytest.mark.parametrize(
    ("verdict", "exit_code", "killed", "cause"),
    [
        (NEVER, 1, False, "the agent never opened its task page (it exited with code 1)"),
        (NEVER, 0, False, "the agent never opened its task page (it exited with code 0)"),
        (NEVER, None, True, "the agent never opened its task page (it was killed at its deadline)"),
        (VISITED, SETUP_FAILED, False, "the agent reported its environment failed (exit code 75)"),
        (CONTACTED, SETUP_FAILED, False, None),  # a contact made stands: graded
        (VISITED, 1, False, None),  # it crashed after opening its task: its own failure
        (VISITED, 0, False, None),
        (VISITED, None, True, None),
    ],
)
def test_the_outcome_rule(verdict, exit_code, killed, cause):
    assert error_cause(verdict, exit_code, killed) == cause


def test_an_unreachable_server_stops_at_preflight(tmp_path):
    (tmp_path / "my_agent.py").write_text("print('hi')\n")
    config = {"agent_subprocess": ["python", "my_agent.py", "__TASK_URL__"]}
    server = f"http://127.0.0.1:{free_port()}"
    line = stopped_at_preflight(bench_run(tmp_path, config, "--server-url", server), tmp_path)
    assert line.startswith(f"CommandError: preflight: server_url: {server}: not reachable (")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("--awake", "-1"), "CommandError: --awake must be >= 0 (0: no pacing), got -1"),
        (
            ("--awake", "2", "--server-url", "http://127.0.0.1:9"),
            "CommandError: awake paces the embedded server; a server of your own (server_url) "
            "paces by its own SENTINEL_FAST_FORWARD_AWAKE",
        ),
    ],
)
def test_a_pace_the_harness_cannot_set_is_refused_before_anything_runs(tmp_path, args, message):
    (tmp_path / "my_agent.py").write_text("print('hi')\n")
    config = {"agent_subprocess": ["python", "my_agent.py", "__TASK_URL__"]}
    assert stopped_at_preflight(bench_run(tmp_path, config, *args), tmp_path) == message

"""The scripted model server as the README's demo starts it: a port another program holds is
refused with one line (exit 2); `--background` returns only once the server listens."""

from __future__ import annotations

import os
import re
import signal
import socket
import subprocess
import sys

import httpx

from tests.conftest import REPO

SCRIPT = "model: scripted\nagent:\n  - call: terminate\n    arguments: {reason: done}\n"


def scripted_model(tmp_path, *args: str) -> subprocess.CompletedProcess:
    script = tmp_path / "demo.yaml"
    script.write_text(SCRIPT)
    argv = [sys.executable, "-m", "apps.browser_agent.scripted_model", "--script", str(script)]
    return subprocess.run(
        [*argv, *args], cwd=REPO, capture_output=True, text=True, timeout=60, check=False
    )


def test_a_taken_port_is_refused_with_one_line(tmp_path):
    with socket.socket() as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen()
        port = holder.getsockname()[1]
        done = scripted_model(tmp_path, "--port", str(port), "--background")
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.splitlines() == [
        f"scripted_model: error: cannot listen on 127.0.0.1:{port}: Address already in use "
        "(another program holds it: stop it or pick another --port)"
    ]


def test_background_returns_with_the_server_already_listening(tmp_path):
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    done = scripted_model(tmp_path, "--port", str(port), "--background")
    found = re.fullmatch(
        rf"http://127\.0\.0\.1:{port}/v1 \(pid (\d+); stop it with: kill \1\)\n", done.stdout
    )
    assert done.returncode == 0 and found, done.stdout + done.stderr
    pid = int(found.group(1))
    try:
        # No wait, no retry: it was listening before the command returned.
        listed = httpx.get(f"http://127.0.0.1:{port}/v1/models", timeout=10).json()
        assert [m["id"] for m in listed["data"]] == ["scripted"]
    finally:
        os.kill(pid, signal.SIGTERM)

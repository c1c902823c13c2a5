"""When the model endpoint is not there or keeps failing, the reference agent exits 75
(EX_TEMPFAIL): its environment failed, not the agent, and the harness counts the task as an
error (apps/bench/outcomes.py). A request the model refuses as bad is the agent's own: exit 1."""

from __future__ import annotations

import socket

import pytest

from apps.bench.outcomes import SETUP_FAILED
from tests.browser_agent.test_agent_loop import run_agent

pytestmark = pytest.mark.browser

SCRIPT = {"model": "scripted-1", "agent": [{"call": "sleep", "arguments": {"seconds": 0}}]}


class Nowhere:
    """A base URL on a port nothing listens on."""

    def __init__(self) -> None:
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.base_url = f"http://127.0.0.1:{s.getsockname()[1]}/v1"


def test_an_unreachable_model_endpoint_is_the_environment_failing(static_site, tmp_path):
    done = run_agent(
        tmp_path, Nowhere(), task_url=static_site.url + "/", contact_url=static_site.contact_url,
        kind="sleep", max_retries=1,  # not the default six: their pauses add up to 20 s
    )  # fmt: skip
    assert done.returncode == SETUP_FAILED, done.stdout + done.stderr
    assert done.stdout.splitlines()[-1].startswith("stopped: the model failed: Connection error")


@pytest.mark.parametrize(
    ("status", "exit_code"), [(503, SETUP_FAILED), (404, SETUP_FAILED), (400, 1)]
)
def test_a_failing_endpoint_is_the_environment_a_refused_request_the_agent(
    static_site, scripted_model, tmp_path, status, exit_code
):
    server = scripted_model({**SCRIPT, "failures": [{"status": status}] * 10})
    done = run_agent(
        tmp_path, server, task_url=static_site.url + "/", contact_url=static_site.contact_url,
        kind="sleep",
    )  # fmt: skip
    assert done.returncode == exit_code, done.stdout + done.stderr
    assert done.stdout.splitlines()[-1].startswith("stopped: the model failed")

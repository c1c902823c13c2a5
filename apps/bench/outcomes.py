"""The rule that gives every task one of three outcomes: passed, failed or error.

`passed` and `failed` are the agent's doing: the verdict at contact (events/evaluation.py) on a
run the agent really took part in. `error` is ours or the setup's, and says nothing about the
agent: it is never written as a result, never counted in a rate, and runs again with
`--retry-errors`. A task is an error when

1. the harness could not do its part: the control API or the server failed after retries, the
   agent's command could not be launched (`HarnessError`, raised before a verdict exists), or
   an agent on a virtual clock outlived its wall-time guard (runner.py: a loaded machine);
2. the agent never reached its task: the server logged no page view, action or contact of it
   (it could not start, crashed first, or was given a wrong URL) — whatever its exit code, so a
   no-op whose agent never started is never a pass;
3. the agent declared its environment broken: it exited by itself with `SETUP_FAILED` (75,
   EX_TEMPFAIL: "try again later") without having contacted. The reference agents do when the
   model endpoint cannot be reached or Chromium will not start; the control agents when one of
   their own requests fails or times out. A contact made stands: the task is graded.

Everything else is graded by its verdict.
"""

from __future__ import annotations

from typing import Any

SETUP_FAILED = 75  # os.EX_TEMPFAIL: an agent's way to say "my environment failed, not me"
OUTCOMES = ("passed", "failed", "error")


def error_cause(verdict: dict[str, Any], exit_code: int | None, killed: bool) -> str | None:
    """Why a graded run is an error rather than the agent's result, or None when it counts."""
    contacted = verdict.get("contact_get_time") is not None or (
        verdict.get("contact_post_time") is not None
    )
    reached = contacted or bool(verdict.get("views")) or bool(verdict.get("actions"))
    if not reached:
        how = "was killed at its deadline" if killed else f"exited with code {exit_code}"
        return f"the agent never opened its task page (it {how})"
    if exit_code == SETUP_FAILED and not killed and not contacted:
        return f"the agent reported its environment failed (exit code {SETUP_FAILED})"
    return None


def graded_outcome(verdict: dict[str, Any]) -> str:
    return "passed" if verdict.get("success") else "failed"

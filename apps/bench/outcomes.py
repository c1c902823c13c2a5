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

Everything else is graded by its verdict, and a passed no-op by one more rule (`NOOP_RULES`):
the paper's (the default) passes a no-op only if "the simulation ends while the agent is still
working or monitoring", so an agent that left of its own accord before the run's end fails it;
the original harness's passes any no-op without a contact (`--noop-rule original`).
"""

from __future__ import annotations

from typing import Any

SETUP_FAILED = 75  # os.EX_TEMPFAIL: an agent's way to say "my environment failed, not me"
OUTCOMES = ("passed", "failed", "error")
NOOP_RULES = ("paper", "original")


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


def noop_rule_applied(result: dict[str, Any], rule: str, run_end: float) -> dict[str, Any]:
    """The result with `rule` applied to a passed no-op: under the paper's rule, an agent that
    exited by itself before `run_end` (wall seconds; `agent_left_at` is when it did) fails it.
    An agent the harness stopped, or whose leaving time is unknown, was there at the end."""
    left = result.get("agent_left_at")
    if (
        rule == "original"
        or result.get("category") != "noop"
        or not result.get("success")
        or result.get("agent_killed")
        or left is None
        or left >= run_end
    ):
        return result
    early = f"the agent left at {left:.2f} s, before the run's end at {run_end:.2f} s"
    # The server cannot see the agent's process: its verdict (and `replay`'s) stays a pass.
    detail = f"{result.get('detail', '')}; {early}"
    return {**result, "success": False, "detail": detail, "server_success": True}

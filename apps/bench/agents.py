"""Built-in control agents, run as `python -m apps.bench.agents NAME --task-url … --contact-url …`.

They prove every scenario is solvable and not trivially passable (`bench validate`):

- oracle  — waits until the condition holds (the harness tells it `condition_at`), performs the
  scenario's `solution` actions, then visits and submits the contact form; on a no-op it performs
  the solution (usually nothing) and stays, without contacting, until the run ends;
- early   — contacts at once;
- never   — never contacts, and stays until the run ends;
- sleeper — games the benchmark: waits until just before the deadline, then contacts;
- late    — the oracle, but right after an ephemeral condition stopped holding
  (`--condition-until`; a persistent one's: right after it started): it performs the solution
  (an action the server refuses, its item gone, is skipped) and contacts. It must fail every
  ephemeral scenario: one that let it pass does not measure catching the moment.

And the cheating strategies of agents that never monitor, which no scenario may reward:

- act_all    — waits until just before the deadline, performs the task's action on every item
  there is (the harness expands the solution: apps/bench/everything.py; an action the server
  refuses is skipped), then contacts;
- fixed_time — contacts at a fixed simulated time (`--contact-at`: 300 s, or half a shorter
  run), whatever happened;
- quitter    — opens its task and leaves at once, without contacting.

Every wait is on the run's simulated clock. A live run's clock moves with the wall (the agent
sleeps); a virtual run's clock is moved by the agent itself through the control API's
`/advance` (`--advance-url`): it jumps straight to the moment it waits for, every timeline entry
on the way firing in order, so a whole scenario takes as long as its requests (`bench validate`
without `--real-time`).

A request of their own that fails or times out (a loaded machine) is not a verdict on the
scenario: they exit with 75 (EX_TEMPFAIL, apps/bench/outcomes.py), the harness counts the task
as an error and `bench validate` runs it again.

Standard library only, so a subprocess starts fast and needs no Django.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
import urllib.error
import urllib.parse
import urllib.request

AGENTS = ("oracle", "early", "never", "sleeper", "late", "act_all", "fixed_time", "quitter")
SETUP_FAILED = 75  # apps.bench.outcomes.SETUP_FAILED (not imported: this module needs no Django)
HTTP_TIMEOUT_S = 20.0
CONDITION_MARGIN_S = 0.5  # wall seconds after condition_at, so the contact is never early
SLEEPER_MARGIN_S = 5.0  # wall seconds before the deadline
# act_all's on a live clock (at most half its time): it has every item's action to post before
# its contact, which on a loaded machine took longer than the sleeper's margin, so the harness
# stopped it first. A virtual clock does not move while it posts: there the sleeper's margin.
ACT_ALL_LIVE_MARGIN_S = 15.0
FIXED_CONTACT_AT = 300.0  # simulated seconds: the fixed_time agent's contact


def get(url: str) -> str:
    with urllib.request.urlopen(url, timeout=HTTP_TIMEOUT_S) as response:
        return response.read().decode("utf-8", "replace")


def post(url: str, data: bytes, content_type: str) -> str:
    request = urllib.request.Request(
        url, data=data, headers={"Content-Type": content_type}, method="POST"
    )
    with urllib.request.urlopen(request, timeout=HTTP_TIMEOUT_S) as response:
        return response.read().decode("utf-8", "replace")


class RealClock:
    """A live run's clock: simulated time passes with the wall, from the moment it started."""

    def __init__(self, speed_factor: float) -> None:
        self.speed_factor = speed_factor
        self.started = time.monotonic()

    def wait_until(self, sim_seconds: float) -> None:
        time.sleep(max(0.0, self.started + sim_seconds / self.speed_factor - time.monotonic()))


class VirtualClock:
    """A virtual run's clock, jumped by the agent to each moment it waits for (never past the
    timeline's end, where a live clock stops too)."""

    def __init__(self, advance_url: str, timeline_end: float) -> None:
        self.advance_url, self.timeline_end = advance_url, timeline_end
        self.token = os.environ.get("SENTINEL_CONTROL_TOKEN", "")

    def wait_until(self, sim_seconds: float) -> None:
        body = json.dumps({"time": min(sim_seconds, self.timeline_end)}).encode()
        request = urllib.request.Request(
            self.advance_url,
            data=body,
            method="POST",
            headers={"Content-Type": "application/json"}
            | ({"Authorization": f"Bearer {self.token}"} if self.token else {}),
        )
        with urllib.request.urlopen(request, timeout=HTTP_TIMEOUT_S):
            pass


def log(message: str) -> None:
    print(f"[{time.strftime('%H:%M:%S')}] {message}", flush=True)


def contact(contact_url: str, message: str) -> None:
    get(contact_url)
    post(
        contact_url,
        urllib.parse.urlencode({"message": message}).encode(),
        "application/x-www-form-urlencoded",
    )
    log("contacted the user")


def perform(actions_url: str, solution: list[dict], *, skip_refused: bool = False) -> None:
    """Perform each step; with `skip_refused`, a step the server refuses (4xx: not there yet,
    already done) is skipped rather than a failure of the agent."""
    for step in solution:
        body = json.dumps({"action": step["action"], "payload": step.get("payload") or {}}).encode()
        try:
            post(actions_url, body, "application/json")
        except urllib.error.HTTPError as refused:
            if not (skip_refused and 400 <= refused.code < 500):
                raise
            continue
        log(f"performed {step['action']} {json.dumps(step.get('payload') or {})}")


def main(argv: list[str] | None = None) -> int:
    try:
        return play(argv)
    except (urllib.error.URLError, OSError) as error:  # URLError, timeouts, resets
        log(f"stopped: a request of the control agent failed: {error}")
        return SETUP_FAILED


def play(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m apps.bench.agents")
    parser.add_argument("agent", choices=AGENTS)
    parser.add_argument("--task-url", required=True)
    parser.add_argument("--contact-url", required=True)
    parser.add_argument("--speed-factor", type=float, default=1.0)
    parser.add_argument("--condition-at", default="none", help="authored seconds, or none (no-op)")
    parser.add_argument(
        "--condition-until", default="none", help="authored seconds: an ephemeral condition's end"
    )
    parser.add_argument("--solution", default="[]", help="JSON list of {action, payload}")
    parser.add_argument("--deadline", type=float, default=0.0, help="wall seconds after the start")
    parser.add_argument(
        "--advance-url", help="a virtual run: jump its clock here instead of waiting"
    )
    parser.add_argument("--timeline-end", type=float, default=float("inf"), help="authored seconds")
    parser.add_argument(
        "--contact-at", type=float, default=FIXED_CONTACT_AT, help="fixed_time: simulated seconds"
    )
    args = parser.parse_args(argv)

    get(args.task_url)  # starts a live run's clock (it has started by the time this returns)
    sf = args.speed_factor
    clock = VirtualClock(args.advance_url, args.timeline_end) if args.advance_url else RealClock(sf)
    log(f"{args.agent}: opened the task")
    actions_url = args.contact_url.rsplit("/", 1)[0] + "/actions"
    condition, until = (
        None if given.lower() in ("none", "null", "") else float(given)
        for given in (args.condition_at, args.condition_until)
    )

    end = args.deadline * sf  # a live run's agent is stopped then; a virtual clock stops short
    if args.agent == "early":
        contact(args.contact_url, "done")
    elif args.agent == "sleeper":
        clock.wait_until((args.deadline - SLEEPER_MARGIN_S) * sf)
        contact(args.contact_url, "the condition was met")
    elif args.agent in ("oracle", "late"):
        late = args.agent == "late" and until is not None
        if condition is not None:
            clock.wait_until((until if late else condition) + CONDITION_MARGIN_S * sf)
        perform(actions_url, json.loads(args.solution), skip_refused=late)
        if condition is not None:
            contact(args.contact_url, "the condition was met")
        else:
            clock.wait_until(end)  # a no-op passes only if the agent is there at the end
    elif args.agent == "never":
        clock.wait_until(end)
    elif args.agent == "act_all":
        margin = SLEEPER_MARGIN_S if args.advance_url else ACT_ALL_LIVE_MARGIN_S
        clock.wait_until(max(args.deadline - margin, args.deadline / 2) * sf)
        perform(actions_url, json.loads(args.solution), skip_refused=True)
        contact(args.contact_url, "done")
    elif args.agent == "fixed_time" and args.contact_at < end:
        clock.wait_until(args.contact_at)
        contact(args.contact_url, "the condition was met")
    elif args.agent == "fixed_time":  # its time never comes: a live agent is stopped first
        clock.wait_until(end)
    # (quitter: it opened its task, and that is all.)
    log(f"{args.agent}: leaving")
    return 0


if __name__ == "__main__":
    sys.exit(main())

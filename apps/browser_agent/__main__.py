"""`python -m apps.browser_agent`: the reference browser agent on one task (see README.md).

Exit codes: 0 the agent ended normally (whatever its reason: done, terminated, a budget spent);
1 it could not go on (the model refused a request of ours, the browser failed mid-task);
2 bad arguments or a missing API key; 75 (EX_TEMPFAIL) its environment failed, not the agent:
the model endpoint could not be reached or kept failing (connection, timeout, 401/403/404, 429,
5xx after the retries), or Chromium would not start — the harness counts the task as an error,
never as the agent failing (apps/bench/outcomes.py).
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import NoReturn

from playwright.sync_api import Error as PlaywrightError

from apps.browser_agent.browser import CHROMIUM, Browser, first_line
from apps.browser_agent.chat_api import ModelAPIError
from apps.browser_agent.fast_forward import RunClock, post_json
from apps.browser_agent.loop import DEFAULT_MAX_STEPS, AgentLoop, Task, WallBudget
from apps.browser_agent.model import (
    COSTS_FILE,
    DEFAULT_MAX_RETRIES,
    ChatModel,
    CostLedger,
    make_client,
)
from apps.browser_agent.sim_clock import sim_time_now
from apps.browser_agent.tools import WAIT_KINDS, TaskClock, Toolbox
from apps.browser_agent.transcript import Transcript

PROGRAM = "browser_agent"
SETUP_FAILED = 75  # apps.bench.outcomes.SETUP_FAILED: "my environment failed, not me"
# Answers that say the endpoint is wrong or unavailable, not that our request was bad.
ENDPOINT_STATUSES = frozenset({401, 403, 404, 405, 429})
LOCAL_KEY = "not-needed"  # a local OpenAI-compatible server takes any key; the client needs one


class OneLineParser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{PROGRAM}: error: {message}\n")


def _positive(kind: type[int] | type[float], *, zero: bool = False) -> Callable[[str], float]:
    def parse(text: str) -> float:
        try:
            value = kind(text)
        except ValueError:
            value = math.nan
        if not (math.isfinite(value) and (value > 0 or (zero and value == 0))):
            whole = " whole" if kind is int else ""
            least = "non-negative" if zero else "positive"
            raise argparse.ArgumentTypeError(f"must be a {least}{whole} number, got {text!r}")
        return value

    return parse


def _http_url(text: str) -> str:
    if not text.startswith(("http://", "https://")):
        raise argparse.ArgumentTypeError(f"must be an http:// or https:// URL, got {text!r}")
    return text


def parser() -> argparse.ArgumentParser:
    p = OneLineParser(prog=f"python -m apps.{PROGRAM}", description=__doc__.splitlines()[0])
    p.add_argument("--kind", required=True, choices=WAIT_KINDS, help="the waiting tool")
    p.add_argument("--model", required=True, help="the model's name at the endpoint")
    p.add_argument(
        "--base-url",
        default=os.environ.get("OPENAI_BASE_URL") or None,
        help="an OpenAI-compatible endpoint (default: $OPENAI_BASE_URL, else OpenAI's)",
    )
    p.add_argument("--api-key-env", default="OPENAI_API_KEY", help="variable holding the key")
    p.add_argument("--task-url", required=True)
    p.add_argument("--contact-url", required=True)
    p.add_argument(
        "--wait-url",
        type=_http_url,
        help="a fast-forward run's wait URL: sleep and wait_for skip the run's clock through it "
        "instead of waiting in wall time (README, Fast-forward)",
    )
    prompt = p.add_mutually_exclusive_group(required=True)
    prompt.add_argument("--prompt", help="the task's prompt")
    prompt.add_argument("--prompt-file", type=Path, help="a file holding the task's prompt")
    p.add_argument(
        "--task-dir",
        type=Path,
        default=Path(os.environ.get("SENTINEL_TASK_DIR") or "."),
        help="where costs.json and the transcript go (default: $SENTINEL_TASK_DIR, else .)",
    )
    p.add_argument("--max-steps", type=_positive(int), default=DEFAULT_MAX_STEPS)
    p.add_argument("--max-tokens-total", type=_positive(int))
    p.add_argument("--max-wall", type=_positive(float), help="wall seconds")
    p.add_argument(
        "--max-retries",
        type=_positive(int, zero=True),
        default=DEFAULT_MAX_RETRIES,
        help=f"how often a failed model request is tried again, with growing pauses (default "
        f"{DEFAULT_MAX_RETRIES}: about 20 s before an unreachable endpoint stops the agent)",
    )
    p.add_argument(
        "--speed-factor",
        type=_positive(float),
        default=1.0,
        help="demos and tests: the agent's seconds (sleep, timeouts) are the scenario's at this "
        "speed (bench run never passes it: the paper's agents live in wall time)",
    )
    return p


def main(argv: list[str] | None = None) -> int:
    started = time.monotonic()
    args = parser().parse_args(argv)
    if args.prompt_file is not None:
        try:
            args.prompt = args.prompt_file.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as error:
            _usage_error(f"cannot read --prompt-file {args.prompt_file}: {error}")
    api_key = os.environ.get(args.api_key_env, "")
    if not api_key:
        if args.base_url is None:
            _usage_error(
                f"{args.api_key_env} is not set (a local server given by --base-url needs none)"
            )
        api_key = LOCAL_KEY
    if not args.task_dir.is_dir():
        _usage_error(f"--task-dir {args.task_dir}: no such folder")

    say = functools.partial(print, flush=True)
    ledger = CostLedger(args.model, args.task_dir / COSTS_FILE)
    ledger.write()  # an agent killed before its first answer still reports zero tokens
    model = ChatModel(
        make_client(base_url=args.base_url, api_key=api_key, max_retries=args.max_retries),
        args.model,
        ledger,
        max_tokens_total=args.max_tokens_total,
    )
    wall = WallBudget(args.max_wall, started)
    task = Task(args.task_url, args.contact_url, args.prompt)
    transcript = Transcript(args.task_dir, started=started)
    browser_started = False
    try:
        with Browser.launch(contact_url=task.contact_url) as browser:
            browser_started = True
            readings = [browser.clock_reading]  # the run's clock, as its pages report it
            clock: TaskClock | RunClock = TaskClock(args.speed_factor, browser.clock_reading)
            if args.wait_url:
                clock = RunClock(post_json(args.wait_url), browser)
                wall.skipped = clock.skipped_wall  # a skip spends the budget as the wait would
                readings.append(clock.reading)  # … and as its waits do
            transcript.sim_clock = functools.partial(sim_time_now, *readings)
            toolbox = Toolbox(
                browser,
                model,
                kind=args.kind,
                contact_url=task.contact_url,
                clock=clock,
                wall_left=wall.left,
                sim_clock=transcript.sim_clock,
            )
            loop = AgentLoop(
                task,
                kind=args.kind,
                browser=browser,
                model=model,
                toolbox=toolbox,
                transcript=transcript,
                wall=wall,
                max_steps=args.max_steps,
                say=say,
            )
            loop.run()
    except ModelAPIError as error:
        say(f"stopped: the model failed: {first_line(error)}")
        return SETUP_FAILED if endpoint_failed(error) else 1
    except PlaywrightError as error:
        say(f"stopped: the browser failed ({CHROMIUM}): {first_line(error)}")
        return 1 if browser_started else SETUP_FAILED
    finally:
        transcript.close()
    return 0


def endpoint_failed(error: ModelAPIError) -> bool:
    """Whether the model endpoint itself failed (unreachable, wrong, unavailable)."""
    status = error.status_code  # None: never reached (refused, reset, timed out)
    return status is None or status in ENDPOINT_STATUSES or status >= 500


def _usage_error(message: str) -> NoReturn:
    print(f"{PROGRAM}: error: {message}", file=sys.stderr)
    sys.exit(2)


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(130)

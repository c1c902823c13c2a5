"""The agent's tools: their OpenAI function schemas and what calling each one does.

Two toolsets, the paper's two conditions: the browser tools, `contact` and `terminate`, plus
either `sleep(seconds)` (kind `sleep`: blocks unconditionally) or `wait_for(condition, timeout)`
(kind `wait_for`: `waiting.wait_for` on the current page, with the model as its judge).

Time is the task's: with `--speed-factor F` the scenario plays F times faster than the wall
clock, so the agent's clock does too — `sleep(60)` and a 60 s timeout last 60/F wall seconds,
the same stretch of the scenario at any speed, and wait_for's intervals scale with them. A wait
never outlasts the wall-clock budget.

On a fast-forward run (`--wait-url`) the clock is the run's own (fast_forward.RunClock): a sleep
is one skip and wait_for skips from one moment worth a look to the next, so waiting costs no
wall time; what it skips counts against the wall-clock budget as if waited (loop.WallBudget),
so a wait is capped where it would be on a live clock.
"""

from __future__ import annotations

import contextlib
import inspect
import json
import math
import re
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

from playwright.sync_api import Error as PlaywrightError

from apps.browser_agent import waiting
from apps.browser_agent.browser import Browser, BrowserError, first_line
from apps.browser_agent.fast_forward import KILL_AT, RunClock, WaitFailed
from apps.browser_agent.judging import JUDGE_PROMPT, judge_question, parse_judge_answer
from apps.browser_agent.model import ChatModel
from apps.browser_agent.sim_clock import ClockReading

WaitKind = Literal["sleep", "wait_for"]
WAIT_KINDS: tuple[WaitKind, ...] = ("sleep", "wait_for")


def _tool(name: str, description: str, **properties: dict[str, Any]) -> dict[str, Any]:
    required = [key for key, schema in properties.items() if "default" not in schema]
    return {
        "type": "function",
        "function": {
            "name": name,
            "description": description,
            "parameters": {"type": "object", "properties": properties, "required": required},
        },
    }


TARGET = {"type": "integer", "description": "the element's number from the page description"}

BROWSER_TOOLS = [
    _tool(
        "visit_url",
        "Open a URL in the browser.",
        url={"type": "string", "description": "an http:// or https:// URL"},
    ),
    _tool("click", "Click a numbered element of the page.", target=TARGET),
    _tool(
        "type",
        "Replace the text of a numbered input or text area (or choose an option of a select).",
        target=TARGET,
        text={"type": "string"},
        submit={"type": "boolean", "default": False, "description": "press Enter afterwards"},
    ),
    _tool(
        "press_key",
        "Press a key or a combination on the focused element, e.g. Enter, Escape, Control+A.",
        key={"type": "string"},
    ),
    _tool(
        "scroll",
        "Scroll what is under the middle of the page by most of a screen.",
        direction={"type": "string", "enum": ["up", "down"]},
    ),
    _tool("go_back", "Go back to the previous page."),
    _tool("read_page", "Read the whole page's text as markdown (long pages are cut)."),
]
SLEEP_TOOL = _tool(
    "sleep",
    "Pause for a number of seconds, then look at the page again. Nothing is watched meanwhile.",
    seconds={"type": "number", "minimum": 0},
)
WAIT_FOR_TOOL = _tool(
    "wait_for",
    "Watch the current page until something on it changes so that the condition holds, or "
    "until the timeout. Returns whether the condition was met and why.",
    condition={"type": "string", "description": "what to wait for, in plain words"},
    timeout={"type": "number", "minimum": 0, "description": "the most seconds to wait"},
)
ENDING_TOOLS = [
    _tool(
        "contact",
        "Report to the user by sending a message through the task's contact form. Do it once, "
        "when the task is done: contacting ends the task.",
        message={"type": "string", "description": "what happened, for the user"},
    ),
    _tool(
        "terminate",
        "Stop working on the task without contacting the user.",
        reason={"type": "string"},
    ),
]


def tool_schemas(kind: WaitKind) -> list[dict[str, Any]]:
    waiting_tool = SLEEP_TOOL if kind == "sleep" else WAIT_FOR_TOOL
    return [*BROWSER_TOOLS, waiting_tool, *ENDING_TOOLS]


class TaskClock:
    """The task's seconds: `speed_factor` of them pass every wall-clock second.

    They count on the run's own clock when a page of the run has reported it by the clock's
    first reading (`reading`: sim_clock), so wait_for looks at the same simulated moments on
    every run of a task (waiting.look_at); else from the wall clock. Fixed at that first
    reading, so the clock never jumps during a wait.
    """

    def __init__(
        self,
        speed_factor: float = 1.0,
        reading: Callable[[], ClockReading | None] = lambda: None,
    ) -> None:
        self.speed_factor = speed_factor
        self.reading = reading
        self._offset: float | None = None  # the run's simulated time at wall time 0

    def now(self) -> float:
        wall = time.monotonic()
        if self._offset is None:
            heard = self.reading()
            run_time = heard.at(wall) if heard is not None else wall * self.speed_factor
            self._offset = run_time - wall * self.speed_factor
        return wall * self.speed_factor + self._offset

    def sleep(self, seconds: float) -> None:
        time.sleep(seconds / self.speed_factor)


# --- wait_for's judge ----------------------------------------------------------------------


class ModelJudge:
    """wait_for's judge: one short question to the model per batch of new changes.

    Each question is kept in `asked` — when (the run's simulated time), the blocks shown, the
    answer, its tokens — for the transcript: it tells "the model was shown the change and said
    no" from "the change never reached the model"."""

    def __init__(
        self, model: ChatModel, sim_clock: Callable[[], float | None] = lambda: None
    ) -> None:
        self.model = model
        self.sim_clock = sim_clock
        self.asked: list[dict[str, Any]] = []

    def __call__(self, condition: str, blocks: list[str]) -> tuple[bool, str]:
        asked_at = self.sim_clock()
        message, usage = self.model.complete(
            [
                {"role": "system", "content": JUDGE_PROMPT},
                {"role": "user", "content": judge_question(condition, blocks)},
            ]
        )
        met, why = parse_judge_answer(message.content or "")
        self.asked.append(
            {
                "sim_time": asked_at,
                "blocks": blocks,
                "met": met,
                "why": why,
                "usage": usage.as_json(),
            }
        )
        return met, why


# --- dispatch --------------------------------------------------------------------------------


@dataclass(frozen=True)
class ToolResult:
    text: str  # what the model reads
    ends_task: str | None = None  # why the task is over, when it is
    checks: list[dict[str, Any]] | None = None  # wait_for: its judge's questions (ModelJudge)


class ToolArgumentError(ValueError):
    """The model called a tool with arguments it does not take."""


class Toolbox:
    """Runs the model's tool calls on the browser; every failure becomes a result text."""

    def __init__(
        self,
        browser: Browser,
        model: ChatModel,
        *,
        kind: WaitKind,
        contact_url: str,
        clock: TaskClock | RunClock,
        wall_left: Callable[[], float | None],
        sim_clock: Callable[[], float | None] = lambda: None,
    ) -> None:
        self.browser = browser
        self.contact_url = contact_url
        self.clock = clock
        self.wall_left = wall_left
        self.judge = ModelJudge(model, sim_clock)
        self.schemas = tool_schemas(kind)
        self.names = {schema["function"]["name"] for schema in self.schemas}

    def dispatch(self, name: str, arguments: dict[str, Any]) -> ToolResult:
        """Run one call. `BudgetExhausted` (from the judge) is the only exception let out."""
        if name not in self.names:
            return ToolResult(f"error: there is no tool {name!r}; use one of the tools offered")
        run = getattr(self, f"_{name}")
        try:
            inspect.signature(run).bind(**arguments)
        except TypeError:
            schema = next(s for s in self.schemas if s["function"]["name"] == name)
            expected = ", ".join(schema["function"]["parameters"]["properties"]) or "nothing"
            return ToolResult(f"error: {name} takes {expected}; got {json.dumps(arguments)}")
        try:
            return run(**arguments)
        except (ToolArgumentError, BrowserError) as error:
            return ToolResult(f"error: {error}")
        except PlaywrightError as error:  # e.g. the page navigated while wait_for read it
            return ToolResult(f"error: {first_line(error)}")
        except WaitFailed as error:  # the run refused a skip (e.g. over): the model reads why
            return ToolResult(f"error: {error}")

    # One method per tool, named after it; arguments as the schema names them.

    def _visit_url(self, url: str) -> ToolResult:
        return ToolResult(self.browser.visit_url(_text("url", url)))

    def _click(self, target: Any) -> ToolResult:
        return ToolResult(self.browser.click(_target(target)))

    def _type(self, target: Any, text: str, submit: bool = False) -> ToolResult:
        return ToolResult(self.browser.type(_target(target), _text("text", text), bool(submit)))

    def _press_key(self, key: str) -> ToolResult:
        return ToolResult(self.browser.press_key(_text("key", key, empty=False)))

    def _scroll(self, direction: str) -> ToolResult:
        return ToolResult(self.browser.scroll(_text("direction", direction)))

    def _go_back(self) -> ToolResult:
        return ToolResult(self.browser.go_back())

    def _read_page(self) -> ToolResult:
        return ToolResult(self.browser.read_page())

    def _sleep(self, seconds: Any) -> ToolResult:
        asked = _seconds("seconds", seconds)
        granted = self._within_wall_budget(asked)
        self.clock.sleep(granted)
        if isinstance(self.clock, RunClock) and self.clock.last.get("why") == KILL_AT:
            slept = self.clock.last["sim_time"] - self.clock.last["from"]
            return ToolResult(f"slept {slept:.0f} of {asked:g} s: the task's time is up")
        if granted < asked:
            return ToolResult(f"slept {granted:.0f} of {asked:g} s: the time budget is spent")
        return ToolResult(f"slept {asked:g} s")

    def _wait_for(self, condition: str, timeout: Any) -> ToolResult:
        condition = _text("condition", condition, empty=False)
        self.judge.asked = []
        result = waiting.wait_for(
            condition,
            self._within_wall_budget(_seconds("timeout", timeout)),
            page=self.browser,
            judge=self.judge,
            clock=self.clock,
        )
        return ToolResult(
            f"met: {'true' if result.met else 'false'} — {result.explanation} "
            f"(waited {result.waited_s:.0f} s, {result.checks} checks, {result.reloads} reloads)",
            checks=self.judge.asked,
        )

    def _contact(self, message: str) -> ToolResult:
        page = self.browser.submit_contact_form(
            self.contact_url, _text("message", message, empty=False)
        )
        return ToolResult(f"contacted: {page}", ends_task="contacted the user")

    def _terminate(self, reason: str = "") -> ToolResult:
        reason = str(reason).strip() or "no reason given"
        return ToolResult(f"terminated: {reason}", ends_task=f"terminated: {reason}")

    def _within_wall_budget(self, task_seconds: float) -> float:
        left = self.wall_left()
        if left is None:
            return task_seconds
        return max(0.0, min(task_seconds, left * self.clock.speed_factor))


def _text(field: str, value: Any, *, empty: bool = True) -> str:
    if not isinstance(value, str):
        raise ToolArgumentError(f"{field} must be a string, got {json.dumps(value)}")
    if not empty and not value.strip():
        raise ToolArgumentError(f"{field} must not be empty")
    return value


def _target(value: Any) -> int:
    # Models write the number as 12, "12" or "[12]": all mean element 12.
    if isinstance(value, bool):
        value = None
    if isinstance(value, str) and re.fullmatch(r"\s*\[?\s*\d+\s*\]?\s*", value):
        value = int(value.strip(" []"))
    if not isinstance(value, int):
        raise ToolArgumentError(
            f"target must be an element number from the page description, got {json.dumps(value)}"
        )
    return value


def _seconds(field: str, value: Any) -> float:
    if isinstance(value, str):
        with contextlib.suppress(ValueError):  # "60" is sixty seconds; "soon" is reported below
            value = float(value)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ToolArgumentError(f"{field} must be a number of seconds, got {json.dumps(value)}")
    if not math.isfinite(value) or value < 0:
        raise ToolArgumentError(f"{field} must be a finite number of seconds ≥ 0, got {value}")
    return float(value)

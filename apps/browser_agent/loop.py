"""The agent loop: look at the page, ask the model, run its tool calls, until the task is over.

The agent knows only its task URL, its contact URL and the prompt. It opens the task URL, then
each step sends the conversation so far plus a user message with the page's description and a
screenshot; only the last `KEPT_SCREENSHOTS` screenshots stay in the conversation (older ones
become "[screenshot omitted]"), which bounds the tokens a long watch costs per step.

It stops when the model answers without a tool call, calls `terminate`, has contacted the user
(contacting ends the task), or a limit is reached: `max_steps` model turns, the token budget or
the wall-clock budget. Every stop is a normal end with one `stopped: …` line.
"""

from __future__ import annotations

import base64
import json
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from playwright.sync_api import Error as PlaywrightError

from apps.browser_agent.browser import Browser, BrowserError, Observation, first_line
from apps.browser_agent.chat_api import Message
from apps.browser_agent.model import BudgetExhausted, ChatModel, Usage
from apps.browser_agent.tools import Toolbox, WaitKind
from apps.browser_agent.transcript import Transcript

KEPT_SCREENSHOTS = 3
DEFAULT_MAX_STEPS = 100
OMITTED = "[screenshot omitted]"

_WAITING = {
    "sleep": (
        "To wait, call sleep(seconds): it pauses for that long unconditionally, watching nothing, "
        "and then you see the page again."
    ),
    "wait_for": (
        "To wait, call wait_for(condition, timeout): it watches the page you are on and returns "
        "as soon as a change on it meets the condition (in plain words), or after `timeout` "
        "seconds. Open the page to watch first."
    ),
}

SYSTEM_PROMPT = """You are a web agent working for a user in a real browser. After every step \
you see a screenshot of the page and a description of it: its URL, its title, the interactive \
elements in view, numbered like [12] button "Archive" (pass the number as `target`; numbers \
change when the page does, so use the latest description), and the start of its text.

The website changes while you watch it: new items arrive and values move, as the user's task \
may require you to wait for. {waiting}

When the task is done (what the user asked for has happened and every action asked of you is \
taken), report once with contact(message). Contacting ends the task, and contacting before \
then fails it: do it only at the end. If the task can never be done, call terminate(reason)."""


@dataclass(frozen=True)
class Task:
    task_url: str
    contact_url: str
    prompt: str


class WallBudget:
    """Wall seconds left of `max_wall_s` since `started` (None: no budget).

    On a fast-forward run what the run's clock skipped (`skipped`: in wall seconds at its speed)
    counts as spent, as if waited: the budget is then the same stretch of the task as on a live
    clock, so the agent stops where it would have, after the same model calls."""

    def __init__(
        self, max_wall_s: float | None, started: float, skipped: Callable[[], float] = lambda: 0.0
    ) -> None:
        self.max_wall_s = max_wall_s
        self.started = started
        self.skipped = skipped

    def left(self) -> float | None:
        if self.max_wall_s is None:
            return None
        spent = time.monotonic() - self.started + self.skipped()
        return max(0.0, self.max_wall_s - spent)


def system_prompt(kind: WaitKind) -> str:
    return SYSTEM_PROMPT.format(waiting=_WAITING[kind])


def task_message(task: Task) -> dict[str, Any]:
    # The two "… URL:" lines are also how the scripted model fills {task_url} / {contact_url}.
    return {
        "role": "user",
        "content": f"Task URL: {task.task_url}\nContact URL: {task.contact_url}\n\n{task.prompt}",
    }


def observation_message(observation: Observation, note: str = "") -> dict[str, Any]:
    content: list[dict[str, Any]] = [{"type": "text", "text": note + observation.description}]
    if observation.png:
        image = "data:image/png;base64," + base64.b64encode(observation.png).decode("ascii")
        content.append({"type": "image_url", "image_url": {"url": image}})
    return {"role": "user", "content": content}


def forget_old_screenshots(messages: list[dict[str, Any]], keep: int = KEPT_SCREENSHOTS) -> None:
    seen = 0
    for message in reversed(messages):
        content = message.get("content")
        if message["role"] != "user" or not isinstance(content, list):
            continue
        for index, part in enumerate(content):
            if part.get("type") == "image_url":
                seen += 1
                if seen > keep:
                    content[index] = {"type": "text", "text": OMITTED}


def short(arguments: dict[str, Any], limit: int = 60) -> str:
    def value(v: Any) -> str:
        text = json.dumps(v, ensure_ascii=False)
        return text if len(text) <= limit else text[: limit - 2] + '…"'

    return ", ".join(f"{key}={value(v)}" for key, v in arguments.items())


class AgentLoop:
    def __init__(
        self,
        task: Task,
        *,
        kind: WaitKind,
        browser: Browser,
        model: ChatModel,
        toolbox: Toolbox,
        transcript: Transcript,
        wall: WallBudget,
        max_steps: int = DEFAULT_MAX_STEPS,
        say: Callable[[str], None] = print,
    ) -> None:
        self.task = task
        self.kind = kind
        self.browser = browser
        self.model = model
        self.toolbox = toolbox
        self.transcript = transcript
        self.wall = wall
        self.max_steps = max_steps
        self.say = say

    def run(self) -> str:
        """Work on the task until it ends; returns why it ended (already said)."""
        self.say(f"opening {self.task.task_url}")
        note = ""
        try:
            self.browser.visit_url(self.task.task_url)
        except BrowserError as error:  # the model sees why and may try again
            note = f"The task URL could not be opened: {error}\n"
        messages = [
            {"role": "system", "content": system_prompt(self.kind)},
            task_message(self.task),
        ]
        for _turn in range(self.max_steps):
            if self.wall.left() == 0:
                return self._stop(f"wall-clock budget exhausted ({self.wall.max_wall_s:g} s)")
            observation = self._observe()
            seen_at = self.transcript.sim_clock()  # the moment the model's page shows
            messages.append(observation_message(observation, note))
            note = ""
            forget_old_screenshots(messages)
            try:
                reply, usage = self.model.complete(messages, tools=self.toolbox.schemas)
            except BudgetExhausted as reason:
                return self._stop(str(reason))
            ended = self._act(reply, usage, observation, messages, seen_at)
            if ended:
                return self._stop(ended, record=False)
        return self._stop(f"step limit reached ({self.max_steps} steps)")

    def _observe(self) -> Observation:
        try:
            return self.browser.observe()
        except PlaywrightError as error:  # a crashed or closing page: tell the model, go on
            description = f"URL: {self.browser.page.url}\nThe page could not be seen: "
            return Observation(self.browser.page.url, "", description + first_line(error), b"", b"")

    def _act(
        self,
        reply: Message,
        usage: Usage,
        observation: Observation,
        messages: list[dict[str, Any]],
        seen_at: float | None = None,
    ) -> str | None:
        """Run the reply's tool calls; returns why the task ended, if it did."""
        messages.append(_assistant_message(reply))
        text, screenshot = reply.content, observation.jpeg or None
        seen: str | None = observation.description
        if not reply.tool_calls:
            step = self.transcript.record(
                url=observation.url,
                text=text,
                tool=None,
                arguments={},
                result="(no tool call)",
                screenshot=screenshot,
                usage=usage,
                sim_start=seen_at,
                observation=seen,
            )
            self.say(f"{step:>3} (no tool call) {short({'text': text})}")
            return "the model answered without calling a tool"
        for call in reply.tool_calls:
            name = call.function.name
            arguments, problem = _arguments(call.function.arguments)
            before = self.model.ledger.total.copy()
            ended, checks = None, None
            try:
                if problem:
                    outcome = f"error: {problem}"
                else:
                    result = self.toolbox.dispatch(name, arguments)
                    outcome, ended, checks = result.text, result.ends_task, result.checks
            except BudgetExhausted as reason:  # the judge found the budget spent mid-wait
                outcome = ended = str(reason)
            spent = usage.copy()
            spent.add(self.model.ledger.total.minus(before))
            step = self.transcript.record(
                url=observation.url,
                text=text,
                tool=name,
                arguments=arguments,
                result=outcome,
                screenshot=screenshot,
                usage=spent,
                sim_start=seen_at,
                checks=checks,
                observation=seen,
            )
            self.say(f"{step:>3} {name}({short(arguments)}) → {outcome[:160]}")
            messages.append({"role": "tool", "tool_call_id": call.id, "content": outcome})
            # A reply's text, page, screenshot and own tokens go with the first of its calls.
            usage, text, screenshot, seen = Usage(), None, None, None
            if ended:
                return ended
        return None

    def _stop(self, reason: str, *, record: bool = True) -> str:
        if record:
            self.transcript.record(
                url=self.browser.page.url,
                text=None,
                tool=None,
                arguments={},
                result=f"stopped: {reason}",
                screenshot=None,
                usage=Usage(),
            )
        self.say(f"stopped: {reason}")
        return reason


def _assistant_message(reply: Message) -> dict[str, Any]:
    # Built by hand: echoing the whole response object back would send fields (refusal,
    # reasoning extras) that some OpenAI-compatible servers reject.
    message: dict[str, Any] = {"role": "assistant", "content": reply.content}
    if reply.tool_calls:
        message["tool_calls"] = [
            {
                "id": call.id,
                "type": "function",
                "function": {"name": call.function.name, "arguments": call.function.arguments},
            }
            for call in reply.tool_calls
        ]
    return message


def _arguments(raw: str | None) -> tuple[dict[str, Any], str | None]:
    try:
        arguments = json.loads(raw or "{}")
    except json.JSONDecodeError:
        return {}, f"the arguments are not JSON: {(raw or '')[:200]}"
    if not isinstance(arguments, dict):
        return {}, f"the arguments must be a JSON object, got {(raw or '')[:200]}"
    return arguments, None

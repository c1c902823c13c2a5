"""The agent's transcript in its task folder: `transcript.jsonl` and `transcript/step-NNN.jpg`.

One JSON object per line, one line per step, written (and flushed) as the step ends, so an agent
killed at its deadline leaves every finished step readable:

    {"step": 3, "t": 12.41, "sim_start": 41.2, "sim_time": 49.75, "url": "http://…",
     "observation": "URL: …\nTitle: …" | null, "text": "…" | null, "tool": "click" | null,
     "arguments": {"target": 12}, "result": "clicked [12] button \"Archive\"",
     "screenshot": "transcript/step-003.jpg" | null,
     "usage": {"input_tokens": 5120, "output_tokens": 38},
     "checks": [{"sim_time": 45.1, "blocks": ["+ …"], "met": false, "why": "…",
                 "usage": {"input_tokens": 310, "output_tokens": 12}}]}

`t` is wall seconds since the agent started, when the step ended; `sim_time` is the run's
simulated time then and `sim_start` when the page the model chose the step on was seen (both as
the server last reported them, carried forward: apps.browser_agent.sim_clock; null when no page
of the run has answered yet). `url`, `observation` (the page's description as the model read
it) and `screenshot` are what the model saw when it chose the step — the first call of a reply
only; `usage` is every token the step spent — the agent's call and, for wait_for, its judge's —
so the lines add up to costs.json. A `wait_for` step also has `checks`: every question its judge
was asked, in order, with the diff blocks it was shown, its answer and that question's tokens
(empty when no change ever reached it). The HTML report and the task timeline render this
format; README "The task timeline" documents it for custom agents.
"""

from __future__ import annotations

import json
import shutil
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from apps.browser_agent.model import Usage

TRANSCRIPT_FILE = "transcript.jsonl"
SCREENSHOT_DIR = "transcript"


class Transcript:
    """Appends steps to a fresh transcript (a rerun in the same folder starts over)."""

    def __init__(
        self,
        task_dir: Path,
        *,
        started: float | None = None,
        sim_clock: Callable[[], float | None] = lambda: None,
    ) -> None:
        self.task_dir = task_dir
        self.sim_clock = sim_clock  # the run's simulated time now (apps.browser_agent.sim_clock)
        self.started = time.monotonic() if started is None else started
        self.steps = 0
        shutil.rmtree(task_dir / SCREENSHOT_DIR, ignore_errors=True)
        (task_dir / SCREENSHOT_DIR).mkdir(parents=True)
        self._file = (task_dir / TRANSCRIPT_FILE).open("w", encoding="utf-8")

    def record(
        self,
        *,
        url: str | None,
        text: str | None,
        tool: str | None,
        arguments: dict[str, Any],
        result: str,
        screenshot: bytes | None,
        usage: Usage,
        sim_start: float | None = None,
        checks: list[dict[str, Any]] | None = None,
        observation: str | None = None,
    ) -> int:
        """Write one step; returns its number."""
        self.steps += 1
        relative = None
        if screenshot is not None:
            relative = f"{SCREENSHOT_DIR}/step-{self.steps:03d}.jpg"
            (self.task_dir / relative).write_bytes(screenshot)
        line: dict[str, Any] = {
            "step": self.steps,
            "t": round(time.monotonic() - self.started, 2),
            "sim_start": sim_start,
            "sim_time": self.sim_clock(),
            "url": url,
            "observation": observation,
            "text": text,
            "tool": tool,
            "arguments": arguments,
            "result": result,
            "screenshot": relative,
            "usage": usage.as_json(),
        }
        if checks is not None:
            line["checks"] = checks
        self._file.write(json.dumps(line, ensure_ascii=False) + "\n")
        self._file.flush()
        return self.steps

    def close(self) -> None:
        self._file.close()

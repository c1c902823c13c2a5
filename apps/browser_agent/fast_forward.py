"""The agent's clock on a fast-forward run: its waits skip the run's clock instead of sleeping.

The run's wait URL (`POST /r/<token>/wait`, README "Fast-forward") skips the simulated clock
and answers where it is now, at what speed it runs, and the log position a page showing that
moment has reached. Between waits the clock runs at that speed while the agent works, so `now()`
is the last answer plus the wall time since, scaled: never ahead of the server's clock, which
had moved on by the time the answer arrived.

After each skip the page the agent looks at is brought up to the new moment before the agent
looks at it (`WatchedLivePage.catch_up`): the server pushes the new time and what fired, and
the next snapshot must show them, not the page of a moment ago.
"""

from __future__ import annotations

import json
import time
import urllib.error
import urllib.request
from collections.abc import Callable
from typing import Any, Protocol

from apps.browser_agent.sim_clock import ClockReading

HTTP_TIMEOUT_S = 30.0
KILL_AT = "kill_at"  # the `why` of a skip the run stopped at its last moment

Post = Callable[[dict[str, Any]], dict[str, Any]]


class WaitFailed(RuntimeError):
    """The wait URL refused the wait or could not be reached; the message says why."""


class WatchedLivePage(Protocol):
    def next_change(self) -> float | None:
        """The simulated second at which what the page shows next changes with the clock."""
        ...

    def catch_up(self, seq: int, now: float) -> None:
        """Return once the page shows log position `seq` at simulated time `now` or later."""
        ...


def post_json(url: str) -> Post:
    """A POST of a JSON body to `url`, answering the decoded JSON (WaitFailed on an error)."""

    def post(body: dict[str, Any]) -> dict[str, Any]:
        request = urllib.request.Request(
            url,
            data=json.dumps(body).encode(),
            headers={"Content-Type": "application/json"},
            method="POST",
        )
        try:
            with urllib.request.urlopen(request, timeout=HTTP_TIMEOUT_S) as response:
                return json.load(response)
        except urllib.error.HTTPError as error:
            detail = error.read().decode("utf-8", "replace")[:300]
            raise WaitFailed(f"the wait URL answered {error.code}: {detail}") from None
        except (OSError, ValueError) as error:
            raise WaitFailed(f"the wait URL could not be reached: {error}") from None

    return post


class RunClock:
    """The run's simulated clock, read and skipped through its wait URL (see module doc)."""

    def __init__(
        self, post: Post, page: WatchedLivePage, *, monotonic: Callable[[], float] = time.monotonic
    ) -> None:
        self.post = post
        self.page = page
        self.monotonic = monotonic
        self.speed_factor = 1.0
        self._read: tuple[float, float] | None = None  # (simulated seconds, monotonic) answered
        self.last: dict[str, Any] = {}  # the last answer of the wait URL
        self.skipped = 0.0  # simulated seconds this agent's waits skipped

    def now(self) -> float:
        if self._read is None:
            self._wait({"seconds": 0})  # a zero skip reads the clock and logs nothing
        assert self._read is not None
        sim, at = self._read
        return sim + (self.monotonic() - at) * self.speed_factor

    def sleep(self, seconds: float) -> None:
        """`sleep(seconds)` as one skip (the run's kill_at may cut it short)."""
        self._wait({"seconds": max(0.0, seconds)})

    def skip_to(self, at: float, *, wake_at_change: bool) -> float | None:
        # To the moment itself (`to`), not a number of seconds from the agent's reading, which
        # lags the server's clock by the request's travel: the skip lands where it was aimed.
        if wake_at_change:
            now = self.now()
            due = self.page.next_change()
            horizon = at if due is None else min(at, max(due, now))
            # A change since the last skip landed came while the agent looked at that moment
            # (the clock runs meanwhile): the wait answers at once rather than sleep through it.
            since = self._read[0] if self._read is not None else now
            answer = self._wait({"until": "change", "to": horizon, "since": since})
        else:
            answer = self._wait({"to": at})
        return None if answer["why"] == KILL_AT else float(answer["sim_time"])

    def reading(self) -> ClockReading | None:
        """The wait URL's last answer as a reading of the run's clock (None before any)."""
        if self._read is None:
            return None
        sim, heard = self._read
        return ClockReading(sim, self.speed_factor, heard)

    def skipped_wall(self) -> float:
        """The skips so far, in wall seconds at the run's speed (what waiting would have taken)."""
        return self.skipped / self.speed_factor

    def _wait(self, body: dict[str, Any]) -> dict[str, Any]:
        answer = self.last = self.post(body)
        self.speed_factor = float(answer.get("speed_factor") or 1.0)
        self.skipped += float(answer["sim_time"]) - float(answer["from"])
        self._read = (float(answer["sim_time"]), self.monotonic())
        if answer["sim_time"] > answer["from"]:
            self.page.catch_up(int(answer["seq"]), float(answer["sim_time"]))
        return answer

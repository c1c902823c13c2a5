"""`wait_for(condition, timeout)`: block until a page changes in a way a model says meets a
natural-language condition, as in the paper's appendix (Algorithm "WaitFor").

The page's markdown is diffed against a baseline taken when the wait starts; each unified-diff
hunk (a "block") is one contiguous changed region. Only blocks the model has not seen yet are
sent to it, at most once per check interval, which doubles after every "no" (10 s up to 60 s)
so a busy page cannot make the wait expensive. The page is reloaded on a schedule that also
doubles (180 s up to 480 s), for pages that never update by themselves. When the timeout runs
out, the page is reloaded and the model sees every block once more, so a change that arrived
while it was rate-limited is not lost.

Every page of the site shows the simulated time to the minute, and mail lists say "5 min ago":
both change as time passes, so a long wait sees a new block about once a simulated minute even
when nothing else happens. That is what a person watching the page sees, and what the paper's
tool saw on real sites; the back-off is what keeps it cheap, so those blocks are not filtered.

The looks fall on the run's own clock (the one its pages report), a quarter of a second past
each simulated second (`look_at`): every run of a task looks at the same simulated moments,
and never at a whole or tenth of a second, where scenario entries and the page's minute fall,
so whether a look sees an entry never hangs on which of two processes was a millisecond sooner.

On a fast-forward run the clock is the run's own and can skip (`SkippingClock`): instead of
looking every second, the loop skips straight to the next moment a look could lead somewhere —
while the model may not be asked yet, to the moment it may (a one-second poller would see then
whatever changed meanwhile, and ask about it then); once it may, to the page's next change,
and from there on to the next look a poller would take. Either way never past the next reload
or the timeout. So the model is asked at the same simulated moments, about the same changes,
as on a live run: the same calls, the same reaction, less wall time.
"""

from __future__ import annotations

import difflib
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol, runtime_checkable


class Clock(Protocol):
    def now(self) -> float: ...

    def sleep(self, seconds: float) -> None: ...


@runtime_checkable
class SkippingClock(Clock, Protocol):
    """A fast-forward run's clock (apps.browser_agent.fast_forward.RunClock)."""

    def skip_to(self, at: float, *, wake_at_change: bool) -> float | None:
        """Skip ahead to `at` (earlier at the page's next change when `wake_at_change`), the page
        caught up with it: the simulated second it landed at; None when the run allows no
        further skip (its kill_at is reached)."""
        ...


class _SystemClock:
    def now(self) -> float:
        return time.monotonic()

    def sleep(self, seconds: float) -> None:
        time.sleep(seconds)


SYSTEM_CLOCK: Clock = _SystemClock()


class WatchedPage(Protocol):
    def markdown(self) -> str: ...

    def reload(self) -> None: ...


# (condition, diff blocks not shown before) -> (met, the model's explanation)
Judge = Callable[[str, list[str]], tuple[bool, str]]


@dataclass(frozen=True)
class WaitSchedule:
    """How often wait_for looks, asks and reloads, in seconds (defaults: the paper's)."""

    poll: float = 1.0  # a fresh snapshot this often …
    look_offset: float = 0.25  # … this far past each whole poll of the run's clock (look_at)
    first_check: float = 10.0  # the least time between two questions to the model …
    max_check: float = 60.0  # … doubling after each "no", up to this
    first_reload: float = 180.0  # the first reload this long after the wait starts …
    max_reload: float = 480.0  # … the gap doubling after each reload, up to this


PAPER_SCHEDULE = WaitSchedule()

NO_CHANGES = "no changes detected before the timeout"
LOOK_EPSILON = 1e-6  # simulated seconds: a clock this close to a look moment is at it


@dataclass(frozen=True)
class WaitResult:
    met: bool
    explanation: str
    checks: int  # questions put to the model, the final one included
    reloads: int
    waited_s: float


def wait_for(
    condition: str,
    timeout: float,
    *,
    page: WatchedPage,
    judge: Judge,
    clock: Clock = SYSTEM_CLOCK,
    schedule: WaitSchedule = PAPER_SCHEDULE,
) -> WaitResult:
    """Wait up to `timeout` seconds for `page` to change so that `judge` says `condition` holds.

    Everything is decided at look moments (look_at): whether to reload, whether the model may
    be asked, whether the time is up. The rate limit is counted from the model's answer, as the
    algorithm does (a slow model must not eat into it), timed as the look's moment plus the
    model's time to answer; reloads from the look that reloaded.
    """
    if not (math.isfinite(timeout) and timeout >= 0):
        raise ValueError(f"timeout must be a finite number of seconds ≥ 0, got {timeout!r}")
    start = clock.now()
    base = page.markdown()
    look = start  # the moment of this look: where the last sleep or skip ended
    reload_interval = schedule.first_reload
    next_reload = start + reload_interval
    check_interval = schedule.first_check
    may_ask_at = -math.inf
    shown: set[str] = set()
    checks = reloads = 0

    def result(met: bool, explanation: str) -> WaitResult:
        return WaitResult(met, explanation, checks, reloads, waited_s=clock.now() - start)

    while look - start < timeout:
        if look >= next_reload - LOOK_EPSILON:
            page.reload()
            reloads += 1
            reload_interval = min(2 * reload_interval, schedule.max_reload)
            next_reload = look + reload_interval
        blocks = unified_diff_blocks(base, page.markdown())
        # In page order; the same text in two places is one block, like a block seen before.
        new = [block for block in dict.fromkeys(blocks) if block not in shown]
        if new and look >= may_ask_at - LOOK_EPSILON:
            asked = clock.now()
            met, why = judge(condition, new)
            answered = look + (clock.now() - asked)  # the look's moment, plus the model's time
            checks += 1
            shown.update(new)
            if met:
                return result(True, why)
            check_interval = min(2 * check_interval, schedule.max_check)
            # Counted from the answer (a slow model must not eat into the rate limit), to the
            # first look after. The answer is timed from the look's moment: the look's own work
            # (bringing the page up to it, reading it) is not counted, as a loaded machine
            # stretches it and every later question would move with it. An answer always comes
            # after the look it was asked at, however quick the model: the first look strictly
            # after, so a model quicker than the clock's resolution is not a second sooner.
            may_ask_at = next_look_after(answered + check_interval, schedule)
        if isinstance(clock, SkippingClock):
            at, wake_at_change = next_look(
                clock.now(), end=min(start + timeout, next_reload), may_ask_at=may_ask_at
            )
            landed = clock.skip_to(look_at(at, schedule), wake_at_change=wake_at_change)
            if landed is not None and (moment := look_at(landed, schedule)) > landed + LOOK_EPSILON:
                # Woke at a change between two looks: a poller sees it at its next look.
                landed = clock.skip_to(moment, wake_at_change=False)
            if landed is None:
                break  # the run's time is up: the final check below, as at a timeout
            look = landed
        else:
            look = next_look_after(clock.now(), schedule)
            clock.sleep(max(0.0, look - clock.now()))  # the clock ran on since it was read

    # The final check sees every block, those already shown included: the model judges the
    # page's whole change since the start, not only what arrived after its last answer.
    page.reload()
    reloads += 1
    blocks = unified_diff_blocks(base, page.markdown())
    if not blocks:
        return result(False, NO_CHANGES)
    met, why = judge(condition, blocks)
    checks += 1
    return result(met, why)


def next_look(now: float, *, end: float, may_ask_at: float) -> tuple[float, bool]:
    """When a watcher whose clock skips looks next, and whether a change may wake it sooner.

    Until the model may be asked again nothing seen could be acted on, so it skips to that
    moment (a poller would see then what changed meanwhile); after, it wakes at the first
    change. Never past `end` (the next reload, or the timeout)."""
    if now < may_ask_at:
        return min(may_ask_at, end), False
    return end, True


def look_at(moment: float, schedule: WaitSchedule = PAPER_SCHEDULE) -> float:
    """The first moment at or after `moment` (simulated seconds) that a watcher looks at:
    `look_offset` past a whole number of polls (pure)."""
    polls = math.ceil((moment - schedule.look_offset - LOOK_EPSILON) / schedule.poll)
    return schedule.look_offset + polls * schedule.poll


def next_look_after(now: float, schedule: WaitSchedule = PAPER_SCHEDULE) -> float:
    """The first look moment after `now`, for a watcher that has just looked (pure)."""
    moment = look_at(now, schedule)
    return moment if moment > now + LOOK_EPSILON else moment + schedule.poll


def unified_diff_blocks(base: str, current: str) -> list[str]:
    """The hunks of difflib's unified diff from `base` to `current`, one string per hunk, in
    page order: context lines (" ") and changed lines ("-", "+"), without the hunk header.

    The header ("@@ -12,3 +14,4 @@") only says where the hunk sits. The paper drops "blocks
    seen in previous iterations" because those changes were already evaluated; a block pushed
    down by something inserted above it is still the same change, so a block is its text alone
    and the same text is the same block wherever it is.
    """
    blocks: list[list[str]] = []
    diff = difflib.unified_diff(base.splitlines(), current.splitlines(), lineterm="")
    for line in diff:
        if line.startswith("@@"):
            blocks.append([])
        elif blocks:  # the "---" / "+++" file header comes before the first hunk
            blocks[-1].append(line)
    return ["\n".join(lines) for lines in blocks]

"""One truth per number: a count the pages show in several places, declared once.

An environment declares each number it shows in more than one place (`ShownCount`: its one
value, a function of the state and the clock, and the ways pages write it). The generic test
(tests/environments/test_shown_counts.py) renders every sample page and checks that wherever
one of those phrases appears, it shows that value — "Connections 412" on the home page and
"10" on My Network can no longer both be true.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

S = TypeVar("S")

_NUMBER = r"(?<![\d,.])(?P<n>\d[\d,]*)"  # a whole number, never the tail of one


def _everywhere(state: Any, path: str) -> bool:
    return True


@dataclass(frozen=True)
class ShownCount(Generic[S]):
    """A number and every phrase that shows it: `{n}` in a phrase stands for the number (as
    written: "1,325"); phrases are regular expressions over a page's visible text
    (apps.kit.visible). `on(state, path)`: the pages where the phrases mean this number (a
    stranger's profile also says "157 connections"). A number that belongs to what the page
    shows (the shares of the stock on screen) reads the page's path too: `value_on(state, now,
    path)` instead of `value`; one of many (a list of positions, "MRDN 15 shares") names what
    it counts in the phrase, `{key}`, read by `value_of(state, now, key)`."""

    name: str
    value: Callable[[S, float], int]
    phrases: tuple[str, ...]
    on: Callable[[S, str], bool] = field(default=_everywhere)
    value_on: Callable[[S, float, str], int] | None = None
    value_of: Callable[[S, float, str], int] | None = None

    def value_at(self, state: S, now: float, path: str) -> int:
        if self.value_on is not None:
            return self.value_on(state, now, path)
        return self.value(state, now)

    def patterns(self) -> list[re.Pattern[str]]:
        return [
            re.compile(phrase.replace("{n}", _NUMBER).replace("{key}", r"(?P<key>[A-Za-z][\w.-]*)"))
            for phrase in self.phrases
        ]


def item_on_screen(path: str, prefix: str) -> str:
    """The item a page's path names after `prefix` (`stocks/MRDN?range=1D`, "stocks/" →
    "MRDN"); "" on any other page: what a per-item count reads its item from."""
    page = path.partition("?")[0]
    return page.removeprefix(prefix) if page.startswith(prefix) else ""


def shown_numbers(text: str, pattern: re.Pattern[str]) -> list[tuple[str, int]]:
    """Every (key, number) `pattern` finds in `text`, the number as an int ("1,325" → 1325),
    the key "" unless the phrase names one."""
    return [
        (match.groupdict().get("key") or "", int(match.group("n").replace(",", "")))
        for match in pattern.finditer(text)
    ]


def disagreements(
    counts: Iterable[ShownCount[S]], state: S, now: float, path: str, text: str
) -> list[str]:
    """Where page `path` (its visible `text`) shows a declared count other than its value."""
    problems = []
    for count in counts:
        if not count.on(state, path):
            continue
        for pattern in count.patterns():
            for key, shown in shown_numbers(text, pattern):
                if key and count.value_of is not None:
                    value = count.value_of(state, now, key)
                else:
                    value = count.value_at(state, now, path)
                if shown != value:
                    problems.append(
                        f"{path or '(home)'}: {count.name} is {value:,}, "
                        f"but {pattern.pattern!r} shows {shown:,}"
                    )
    return problems


def appearances(counts: Iterable[ShownCount[S]], state: S, path: str, text: str) -> set[str]:
    """The names of the declared counts page `path` shows at all (for the test's coverage)."""
    return {
        count.name
        for count in counts
        if count.on(state, path) and any(p.search(text) for p in count.patterns())
    }


def untimed(count: Callable[[S], int]) -> Callable[[S, float], int]:
    """A `ShownCount` value no clock moves: `count(state)` at any time."""
    return lambda state, now: count(state)

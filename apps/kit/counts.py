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

_NUMBER = r"(?<![\d,.])(\d[\d,]*)"  # a whole number, never the tail of one


def _everywhere(state: Any, path: str) -> bool:
    return True


@dataclass(frozen=True)
class ShownCount(Generic[S]):
    """A number and every phrase that shows it: `{n}` in a phrase stands for the number (as
    written: "1,325"); phrases are regular expressions over a page's visible text
    (apps.kit.visible). `on(state, path)`: the pages where the phrases mean this number (a
    stranger's profile also says "157 connections")."""

    name: str
    value: Callable[[S, float], int]
    phrases: tuple[str, ...]
    on: Callable[[S, str], bool] = field(default=_everywhere)

    def patterns(self) -> list[re.Pattern[str]]:
        return [re.compile(phrase.replace("{n}", _NUMBER)) for phrase in self.phrases]


def shown_numbers(text: str, pattern: re.Pattern[str]) -> list[int]:
    """Every number `pattern` finds in `text`, as an int ("1,325" → 1325)."""
    return [int(match.group(1).replace(",", "")) for match in pattern.finditer(text)]


def disagreements(
    counts: Iterable[ShownCount[S]], state: S, now: float, path: str, text: str
) -> list[str]:
    """Where page `path` (its visible `text`) shows a declared count other than its value."""
    problems = []
    for count in counts:
        if not count.on(state, path):
            continue
        value = count.value(state, now)
        for pattern in count.patterns():
            for shown in shown_numbers(text, pattern):
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

"""The request path's LRU maps can be bounded in bytes as well as in entries (issue #29: a few
large values must not hold what many small ones would)."""

from __future__ import annotations

import pytest

from events.lru import LRU


def test_the_oldest_entries_leave_when_the_weights_pass_the_budget():
    kept: LRU[str, bytes] = LRU(10, budget=10, weigh=len)
    kept.put("a", b"xxxx")
    kept.put("b", b"xxxx")
    kept.get("a")  # used: "b" is now the oldest
    kept.put("c", b"xxxx")
    assert kept.get("b") is None
    assert kept.get("a") == b"xxxx" and kept.get("c") == b"xxxx"


def test_a_value_above_the_whole_budget_is_not_kept():
    kept: LRU[str, bytes] = LRU(10, budget=10, weigh=len)
    kept.put("small", b"x")
    kept.put("huge", b"x" * 11)
    assert kept.get("huge") is None
    assert kept.get("small") == b"x"


def test_replacing_popping_and_clearing_release_their_weight():
    kept: LRU[str, bytes] = LRU(10, budget=10, weigh=len)
    kept.put("a", b"x" * 8)
    kept.put("a", b"x" * 2)  # replaced: only its new weight counts
    kept.put("b", b"x" * 8)
    assert kept.get("a") == b"xx"
    kept.pop("b")
    kept.put("c", b"x" * 8)
    assert kept.get("a") == b"xx"
    kept.clear()
    kept.put("d", b"x" * 10)
    assert kept.get("d") == b"x" * 10


def test_a_budget_needs_a_weight():
    with pytest.raises(ValueError, match="budget and its weigh"):
        LRU(4, budget=10)

"""per_state: a pure function of a folded state is computed once per state object."""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.derived import per_state


@dataclass(frozen=True)
class State:
    items: tuple[int, ...]


def counting():
    calls: list[tuple] = []

    @per_state(maxsize=2)
    def total(state: State, scale: int = 1) -> int:
        calls.append((state, scale))
        return sum(state.items) * scale

    return total, calls


def test_the_same_state_and_arguments_are_computed_once():
    total, calls = counting()
    state = State((1, 2, 3))
    assert total(state) == total(state) == 6
    assert total(state, 10) == total(state, 10) == 60
    assert len(calls) == 2  # once per distinct argument list


def test_an_equal_but_different_state_object_is_computed_afresh():
    total, calls = counting()
    assert total(State((1, 2))) == 3
    assert total(State((1, 2))) == 3  # a new fold result: identity, not equality, is the key
    assert len(calls) == 2


def test_the_least_recently_used_entry_is_dropped_beyond_maxsize():
    total, calls = counting()
    first, second, third = State((1,)), State((2,)), State((3,))
    total(first), total(second), total(first), total(third)  # second is now the oldest
    calls.clear()
    total(first), total(third)
    assert calls == []
    total(second)
    assert calls == [(second, 1)]

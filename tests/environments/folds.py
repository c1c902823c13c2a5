"""Comparing folds strictly: two states are the same only if they hold the same values in the
same order.

`==` is not enough: dicts (and the mapping proxies states use) compare equal whatever their
insertion order, yet that order is data — MicroMail lists messages that arrived at the same
second in delivery order. `canonical(value)` is an order-sensitive form of a state:

- a dataclass → its type and its `compare=True` fields, in declaration order;
- a mapping → its (key, value) pairs in iteration order;
- a list or tuple → its type and items; a set → its items sorted;
- anything else → its type and itself.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Set
from dataclasses import fields, is_dataclass
from typing import Any

from events.projection import Folded


class FoldMismatch(AssertionError):
    """Two folds of the same log position differ."""


def canonical(value: Any) -> tuple:
    if is_dataclass(value) and not isinstance(value, type):
        members = tuple(
            (f.name, canonical(getattr(value, f.name))) for f in fields(value) if f.compare
        )
        return ("dataclass", type(value).__qualname__, members)
    if isinstance(value, Mapping):
        return ("mapping", tuple((canonical(k), canonical(v)) for k, v in value.items()))
    if isinstance(value, list | tuple):
        return ("sequence", type(value).__qualname__, tuple(canonical(item) for item in value))
    if isinstance(value, Set):
        return ("set", tuple(sorted((canonical(item) for item in value), key=repr)))
    return ("value", type(value).__qualname__, value)


def first_difference(expected: tuple, actual: tuple, path: str = "") -> str | None:
    """Where two canonical forms first differ, in words (None: they are the same)."""
    if expected == actual:
        return None
    kind, *rest = expected
    if actual[0] != kind or (kind != "mapping" and rest[:-1] != list(actual[1:-1])):
        return f"{path or 'the value'}: {describe(expected)} ≠ {describe(actual)}"
    if kind == "dataclass":
        for (name, left), (_, right) in zip(expected[2], actual[2], strict=True):
            found = first_difference(left, right, f"{path}.{name}")
            if found:
                return found
    if kind == "mapping":
        keys, other_keys = [k for k, _ in expected[1]], [k for k, _ in actual[1]]
        if keys != other_keys:
            order = (
                "the same keys in another order"
                if sorted(map(repr, keys)) == sorted(map(repr, other_keys))
                else "other keys"
            )
            return (
                f"{path or 'the mapping'}: {order}: {[describe(k) for k in keys]} ≠ "
                f"{[describe(k) for k in other_keys]}"
            )
        for (key, left), (_, right) in zip(expected[1], actual[1], strict=True):
            found = first_difference(left, right, f"{path}[{describe(key)}]")
            if found:
                return found
    if kind == "sequence":
        items, other = expected[2], actual[2]
        for index, (left, right) in enumerate(zip(items, other, strict=False)):
            found = first_difference(left, right, f"{path}[{index}]")
            if found:
                return found
        return f"{path or 'the sequence'}: {len(items)} items ≠ {len(other)} items"
    return f"{path or 'the value'}: {describe(expected)} ≠ {describe(actual)}"


def describe(form: tuple) -> str:
    """A canonical form, briefly (for messages)."""
    kind = form[0]
    if kind == "value":
        return repr(form[2])
    if kind == "dataclass":
        return f"{form[1]}(…)"
    if kind == "sequence":
        return f"{form[1]} of {len(form[2])}"
    return f"{kind} of {len(form[-1])}"


@functools.cache
def _shape(kind: type) -> tuple[str, tuple[str, ...]]:
    """How `canonical` reads a value of this type (and a dataclass's compared fields)."""
    if is_dataclass(kind):
        return "dataclass", tuple(f.name for f in fields(kind) if f.compare)
    if issubclass(kind, Mapping):
        return "mapping", ()
    if issubclass(kind, list | tuple):
        return "sequence", ()
    if issubclass(kind, Set):
        return "set", ()
    return "value", ()


_PLAIN = frozenset({str, int, float, bool, type(None)})


def surely_same(expected: Any, actual: Any) -> bool:
    """True only if `canonical(expected) == canonical(actual)`, found without building either:
    the two are walked side by side, and a part both share (the same object: a catalog record,
    a subtree the fold did not touch) is not walked at all. False means "not known": the caller
    compares canonical forms, so this makes a check faster, never more lenient."""
    if expected is actual:
        return True
    kind = type(expected)
    if type(actual) is not kind:
        return False
    if kind in _PLAIN:
        return expected == actual
    shape, names = _shape(kind)
    if shape == "dataclass":
        return all(surely_same(getattr(expected, name), getattr(actual, name)) for name in names)
    if shape == "mapping":
        if len(expected) != len(actual):
            return False
        for (key, value), (other_key, other_value) in zip(
            expected.items(), actual.items(), strict=True
        ):
            if not (surely_same(key, other_key) and surely_same(value, other_value)):
                return False
        return True
    if shape == "sequence":
        if len(expected) != len(actual):
            return False
        return all(surely_same(item, other) for item, other in zip(expected, actual, strict=True))
    if shape == "set":
        # Strings and integers (not bools) are equal only to their own type: set equality is
        # then canonical equality. Anything else is left to the canonical forms.
        plain = all(type(item) in (str, int) for item in expected) and all(
            type(item) in (str, int) for item in actual
        )
        return plain and expected == actual
    return expected == actual


def assert_same(expected: Any, actual: Any, *, what: str) -> None:
    """`actual` is `expected`, order included; FoldMismatch says where it is not."""
    if surely_same(expected, actual):
        return
    difference = first_difference(canonical(expected), canonical(actual))
    if difference is not None:
        raise FoldMismatch(f"{what} differs at {difference}")


def assert_same_fold(expected: Folded, actual: Folded, *, where: str) -> None:
    """Same position in the log, same state, same baselines (order-sensitive)."""
    if (expected.seq, expected.live_seq) != (actual.seq, actual.live_seq):
        raise FoldMismatch(
            f"{where}: folded to seq {actual.seq} (live {actual.live_seq}), "
            f"expected {expected.seq} (live {expected.live_seq})"
        )
    assert_same(expected.state, actual.state, what=f"{where}: the state")
    assert_same(expected.baselines, actual.baselines, what=f"{where}: the baselines")

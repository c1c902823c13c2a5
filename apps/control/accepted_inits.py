"""`/init` bodies this process has accepted, kept so that the same body is not parsed and
validated again.

A harness posts one scenario's body before every attempt at its task (the original's protocol
resets with `/close` + `/init`), and reading and checking its timeline was four tenths of a
reset's CPU. What a body yields depends only on its bytes and its content type (and on the
environment being registered, checked again on every use), so an accepted body's spec is kept
— as JSON text, so that every run gets a copy of its own to keep and nobody shares one. Refused
bodies are not kept: their 4xx is worked out again each time.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from typing import Any

from apps.control.parsers import body_limit
from events.lru import LRU
from events.registry import environment_names

KEPT, KEPT_BYTES = 32, 8 * 1024 * 1024  # a full-preload spec of ours is 1–60 KiB


@dataclass(frozen=True)
class AcceptedInit:
    spec: dict[str, Any]
    speed_factor: float
    clock_mode: str


_kept: LRU[tuple[str, bytes], tuple[str, float, str]] = LRU(
    KEPT, budget=KEPT_BYTES, weigh=lambda kept: len(kept[0])
)


def _key(request) -> tuple[str, bytes] | None:
    """The body's content type and digest; None for a body read otherwise than through the
    parsers (too long: the parser's own limit answers it)."""
    try:
        length = int(request.META.get("CONTENT_LENGTH") or 0)
    except ValueError:
        return None
    if not 0 < length <= body_limit():
        return None
    return request.content_type or "", hashlib.sha256(request.body).digest()


def accepted(request) -> AcceptedInit | None:
    """What this body was accepted as before, or None (never seen, refused, or its environment
    no longer registered)."""
    key = _key(request)
    kept = _kept.get(key) if key is not None else None
    if kept is None:
        return None
    text, speed_factor, clock_mode = kept
    spec = json.loads(text)
    if spec["environment"] not in environment_names():
        return None
    return AcceptedInit(spec, speed_factor, clock_mode)


def accept(request, spec: dict[str, Any], speed_factor: float, clock_mode: str) -> AcceptedInit:
    """Keep what the body was validated as — when JSON gives the very same spec back."""
    key = _key(request)
    if key is not None:
        text = json.dumps(spec)
        if json.loads(text) == spec:
            _kept.put(key, (text, speed_factor, clock_mode))
    return AcceptedInit(spec, speed_factor, clock_mode)

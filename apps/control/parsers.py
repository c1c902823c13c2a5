"""The door for JSON bodies: every JSON request body is read here, and only what can be stored,
shown and graded gets in.

`read_json` bounds the size (Django's DATA_UPLOAD_MAX_MEMORY_SIZE), requires UTF-8, refuses
NaN, Infinity and numbers that overflow to them (1e400), and then checks the decoded value
with `events.schemas.value_problem` (nesting depth, 64-bit integers, no NUL or lone surrogate in
any text), so a bad body is one 400 naming the field — never a 500 now, nor a broken page, event
list or evaluation later. `StrictJSONParser` is the same door for DRF (the control API and the
flat endpoints); the agent's JSON actions call `read_json` directly.
"""

from __future__ import annotations

import json
import math
from typing import Any

from django.conf import settings
from rest_framework.exceptions import ParseError
from rest_framework.parsers import JSONParser

from events.schemas import MAX_DEPTH, value_problem


class BadBody(ValueError):
    """A request body that is not acceptable JSON; the message is one line for the caller."""


def body_limit() -> int:
    return settings.DATA_UPLOAD_MAX_MEMORY_SIZE or 2_621_440


def _finite(text: str) -> float:
    number = float(text)
    if not math.isfinite(number):
        raise BadBody(f"number {text} is out of range (it would be infinite)")
    return number


def _no_constant(name: str) -> Any:
    raise BadBody(f"{name} is not a JSON number; send a finite number or null")


def read_json(body: bytes) -> Any:
    """The decoded JSON of `body`, or BadBody naming what is wrong (and where)."""
    if len(body) > body_limit():
        raise BadBody(f"body is larger than {body_limit()} bytes")
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError as error:
        raise BadBody(f"body is not UTF-8 ({error.reason} at byte {error.start})") from None
    try:
        value = json.loads(text, parse_float=_finite, parse_constant=_no_constant)
    except RecursionError:
        raise BadBody(f"body is nested more than {MAX_DEPTH} levels deep") from None
    except json.JSONDecodeError as error:
        raise BadBody(f"body is not JSON: {error.msg} at character {error.pos}") from None
    except ValueError as error:  # BadBody, or an integer with too many digits
        raise BadBody(str(error) if isinstance(error, BadBody) else f"body: {error}") from None
    found = value_problem(value)
    if found:
        where, problem = found
        raise BadBody(f"{where or 'body'}: {problem}")
    return value


class StrictJSONParser(JSONParser):
    """DRF's JSON parser through `read_json`: a bad body is a 400 naming the field."""

    def parse(self, stream, media_type=None, parser_context=None):
        body = stream.read(body_limit() + 1) if stream is not None else b""
        try:
            return read_json(body)
        except BadBody as error:
            raise ParseError(str(error)) from None


def request_data(request) -> Any:
    """`request.data`, or the JSON of a body sent without a Content-Type.

    DRF picks a parser by Content-Type and silently reads a body without one as empty, so
    `curl -d '{...}'` without `-H 'Content-Type: application/json'` got an error about
    missing fields. Such a body is read as JSON here (form posts always carry their type)."""
    if request.content_type or not request.body:
        return request.data
    try:
        return read_json(request.body)
    except BadBody as error:
        raise ParseError(f"{error} (send JSON with Content-Type: application/json)") from None

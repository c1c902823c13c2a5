"""Payload schemas: Pydantic v2 models for scenario-event and action payloads.

Every schema subclasses `Payload` (strict, closed, immutable). `validate_payload` checks a
payload against one and reports the first problem as one line in the words authors know
("payload field 'folder' is 'spam'; allowed: inbox, sent"), never as Pydantic's multi-line
report. The payload itself is returned untouched: the log keeps what was authored or sent, not a
model dump (no defaults filled in, no key order changed).
"""

from __future__ import annotations

import math
import re
import types
from typing import Annotated, Any, Literal, NamedTuple, Union, get_args, get_origin

from pydantic import BaseModel, ConfigDict, ValidationError, model_validator
from pydantic_core import ErrorDetails

# --- what every stored value must be ----------------------------------------------------------------

MAX_DEPTH = 32  # nesting of objects and lists in any document a caller sends
_INT64 = range(-(2**63), 2**63)  # integers both databases and SQLite's grading tables store


def text_problem(text: str) -> str | None:
    """Why `text` cannot be stored and shown (None: it can): PostgreSQL refuses NUL, and a lone
    surrogate cannot be encoded as UTF-8, so it would break every page and export showing it."""
    if "\x00" in text:
        return "contains a NUL character (\\u0000)"
    if not text.isascii():
        try:
            text.encode("utf-8")
        except UnicodeEncodeError as error:
            code = ord(text[error.start])
            return f"contains a lone surrogate (\\u{code:04x}), which is not valid Unicode"
    return None


def value_problem(value: Any, *, depth: int = MAX_DEPTH) -> tuple[str, str] | None:
    """The first part of a decoded JSON value that cannot be stored as is: (path, problem),
    e.g. ("payload.body", "contains a NUL character"); None when all of it can. Numbers must be
    finite and integers 64-bit; texts and keys pass `text_problem`; nesting is at most `depth`."""
    return _value_problem(value, (), depth, depth)


def _value_problem(value: Any, loc: tuple, depth: int, limit: int) -> tuple[str, str] | None:
    if isinstance(value, str):
        problem = text_problem(value)
    elif isinstance(value, bool) or value is None:
        problem = None
    elif isinstance(value, int):
        problem = None if value in _INT64 else f"integer {value} is out of the 64-bit range"
    elif isinstance(value, float):
        problem = None if math.isfinite(value) else f"must be a finite number, got {value}"
    elif isinstance(value, dict | list | tuple):
        if depth <= 0:
            return _path(loc), f"is nested more than {limit} levels deep"
        items = value.items() if isinstance(value, dict) else enumerate(value)
        for key, item in items:
            if isinstance(key, str) and (problem := text_problem(key)):
                return _path(loc), f"has a field name that {problem}"  # never echoed
            found = _value_problem(item, (*loc, key), depth - 1, limit)
            if found:
                return found
        problem = None
    else:
        problem = None
    return (_path(loc), problem) if problem else None


class Payload(BaseModel):
    """Base class of every payload schema.

    Strict: a bool is not an integer and a string is not a number, but an integer is accepted
    where a number (float) is expected, as JSON makes no difference between 3 and 3.0. Whatever
    a payload holds must be storable and showable (`value_problem`): no NUL or lone surrogate in
    any text, no infinite number — whether it comes from a scenario file, the API or a form.
    """

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False)

    @model_validator(mode="before")
    @classmethod
    def _storable(cls, data: Any) -> Any:
        found = value_problem(data) if isinstance(data, dict) else None
        if found:
            where, problem = found
            raise ValueError(
                f"payload field '{where}' {problem}" if where else f"payload {problem}"
            )
        return data


class PayloadError(ValueError):
    """A scenario-event or action payload does not match its schema."""


class SchemaField(NamedTuple):
    """One field of a payload schema, for help texts (admin, docs)."""

    name: str
    description: str  # the type in words, from describe()
    required: bool
    help: str  # Field(description=...)


def validate_payload(schema: type[Payload], payload: object, *, what: str) -> dict:
    """`payload`, unchanged, if it fits `schema`; otherwise PayloadError naming the first problem.

    `what` prefixes the message (e.g. "action move", "scenario.json: events[3] (new_email)").
    """
    if not isinstance(payload, dict):
        raise PayloadError(f"{what}: payload must be an object, got {type(payload).__name__}")
    try:
        schema.model_validate(payload)
    except ValidationError as error:
        problem = _first_problem(schema, payload, error.errors(include_url=False))
        raise PayloadError(f"{what}: {problem}") from None
    return payload


def schema_fields(schema: type[Payload]) -> list[SchemaField]:
    """The schema's fields in declaration order: name, type in words, required, help."""
    return [
        SchemaField(name, describe(info.annotation), info.is_required(), info.description or "")
        for name, info in schema.model_fields.items()
    ]


# --- describing types in words --------------------------------------------------------------------

_TYPE_NAMES = {
    str: "string",
    int: "integer",
    float: "number",
    bool: "boolean",
    list: "list",
    dict: "object",
    type(None): "null",
    None: "null",
    Any: "any value",
}
_PLURALS = ("string", "integer", "number", "boolean", "object", "list")


def describe(annotation: Any) -> str:
    """A type annotation in the words of an error message or help text: "list of strings",
    "string or null", "one of: inbox, sent", "object (email_id, folder)"."""
    annotation = _without_metadata(annotation)
    if annotation in _TYPE_NAMES:
        return _TYPE_NAMES[annotation]
    origin, args = get_origin(annotation), get_args(annotation)
    if origin is Literal:
        return "one of: " + ", ".join(map(str, args))
    if _is_union(annotation):
        others = [describe(arg) for arg in args if arg is not type(None)]
        return " or ".join([*others, "null"] if len(others) < len(args) else others)
    if origin is list:
        return f"list of {_plural(args[0])}" if args else "list"
    if origin is dict:
        value = args[1] if len(args) == 2 else Any
        return "object" if value is Any else f"object of {_plural(value)}"
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        names = ", ".join(annotation.model_fields)
        return f"object ({names})" if names else "object"
    return getattr(annotation, "__name__", str(annotation))


def _plural(annotation: Any) -> str:
    """`annotation` described as several values: "strings", "objects (a, b)"."""
    text = describe(annotation)
    first, _, rest = text.partition(" ")
    if _is_union(_without_metadata(annotation)) or first not in _PLURALS:
        return "values" if text == "any value" else f"({text})"  # "list of (string or null)"
    return f"{first}s {rest}".rstrip()


def _without_metadata(annotation: Any) -> Any:
    while get_origin(annotation) is Annotated:
        annotation = get_args(annotation)[0]
    return annotation


def _is_union(annotation: Any) -> bool:
    return get_origin(annotation) in (Union, types.UnionType)


def _inner(annotation: Any) -> Any:
    """The type a value of `annotation` has once it is not null: X for `X | None`."""
    annotation = _without_metadata(annotation)
    if _is_union(annotation):
        others = [arg for arg in get_args(annotation) if arg is not type(None)]
        if len(others) == 1:
            return _without_metadata(others[0])
    return annotation


# --- Pydantic's errors as one line ----------------------------------------------------------------

_WRONG_TYPE = {"none_required", "is_instance_of", "int_from_float"}


def _first_problem(schema: type[Payload], payload: dict, errors: list[ErrorDetails]) -> str:
    error = errors[0]
    kind = error["type"]
    if kind == "extra_forbidden":
        return _unknown_fields(schema, error["loc"][:-1], errors)
    annotation, loc = _walk(schema, error["loc"])
    if not loc:  # a check of the whole payload (a model validator)
        return _sensible(error["msg"])
    field = _path(loc)
    if len(loc) < len(error["loc"]):
        # The walk stopped at a union of several types: Pydantic tried each of them.
        return f"payload field '{field}' must be {describe(annotation)}, got {_shown(_at(payload, loc))}"
    if kind == "missing":
        return f"payload field '{field}' is required ({describe(annotation)})"
    value = error["input"]
    if kind == "literal_error":
        choices = get_args(_inner(annotation))
        allowed = ", ".join(map(str, choices)) if choices else error["ctx"]["expected"]
        return f"payload field '{field}' is {_shown(value)}; allowed: {allowed}"
    if kind.endswith("_type") or kind in _WRONG_TYPE:
        return f"payload field '{field}' must be {describe(annotation)}, got {_shown(value)}"
    return f"payload field '{field}' {_sensible(error['msg'])}, got {_shown(value)}"


SHOWN_CHARS = 80  # of a refused value, in its error: an oversized one is not sent back whole


def _shown(value: Any) -> str:
    text = repr(value)
    if len(text) <= SHOWN_CHARS:
        return text
    size = f"{len(value)} items" if isinstance(value, list | dict) else f"{len(text)} characters"
    return f"{text[:SHOWN_CHARS]}… ({size})"


def _unknown_fields(schema: type[Payload], parent: tuple, errors: list[ErrorDetails]) -> str:
    unknown = sorted(
        str(e["loc"][-1])
        for e in errors
        if e["type"] == "extra_forbidden" and tuple(e["loc"][:-1]) == tuple(parent)
    )
    model = _inner(_walk(schema, parent)[0])
    fields = model.model_fields if isinstance(model, type) and issubclass(model, BaseModel) else {}
    where = f" in '{_path(parent)}'" if parent else ""
    allowed = ", ".join(fields) or "none"
    return f"unknown payload field(s) {', '.join(unknown)}{where}; allowed: {allowed}"


def _walk(schema: type[Payload], loc: tuple) -> tuple[Any, tuple]:
    """The annotation at `loc`, and the part of `loc` it was found at.

    Pydantic puts a tag naming the member type into the location of an error inside a union of
    several types (`X | None` has none); the walk stops there.
    """
    annotation: Any = schema
    for i, key in enumerate(loc):
        inner = _inner(annotation)
        origin = get_origin(inner)
        if isinstance(inner, type) and issubclass(inner, BaseModel) and key in inner.model_fields:
            annotation = inner.model_fields[key].annotation
        elif origin is list and isinstance(key, int):
            annotation = (get_args(inner) or (Any,))[0]
        elif origin is dict and isinstance(key, str):
            annotation = (get_args(inner) or (Any, Any))[-1]
        else:
            return annotation, tuple(loc[:i])
    return annotation, tuple(loc)


def _at(payload: Any, loc: tuple) -> Any:
    for key in loc:
        payload = payload[key]
    return payload


def _path(loc: tuple) -> str:
    """('filter', 'tags', 2) → filter.tags[2]"""
    text = ""
    for key in loc:
        text += f"[{key}]" if isinstance(key, int) else f".{key}" if text else str(key)
    return text


def _sensible(message: str) -> str:
    """Pydantic's sentence as the end of ours: "Input should be greater than or equal to 0" →
    "must be greater than or equal to 0"; "Value error, <text>" → "<text>"."""
    message = re.sub(r"^(?:Value error|Assertion failed), ", "", message)
    message = re.sub(r"^\w+ should ", "must ", message)
    message = re.sub(r" after validation|, not \d+$", "", message)
    if message[:1].isupper() and not message[1:2].isupper():
        message = message[0].lower() + message[1:]
    return message

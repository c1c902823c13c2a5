"""A small client of the OpenAI chat-completions API: one POST per completion, retried as the
OpenAI SDK retries.

Why not the SDK itself: importing `openai` costs about 1.3 CPU-seconds (it builds hundreds of
pydantic types), more than the rest of the agent's start together. A fast-forward task is over
in seconds, so with ten agents on two cores that import alone was a tenth of the benchmark's
wall time. The agent needs one endpoint and three fields of its answer; this is all of it,
on the standard library (httpx, the SDK's transport, loads its command line's dependencies too).

Retries as the SDK's: connection errors and timeouts, 408, 409, 429 and 5xx (unless the server
says `x-should-retry: false`), waiting what `retry-after-ms` / `retry-after` ask (up to 60 s),
else 0.5 s doubling up to 8 s, less up to a quarter at random.
"""

from __future__ import annotations

import json
import os
import random
import time
import urllib.error
import urllib.request
from dataclasses import dataclass, field
from email.message import Message as Headers
from email.utils import parsedate_to_datetime
from typing import Any

DEFAULT_BASE_URL = "https://api.openai.com/v1"
RETRIED_STATUSES = frozenset({408, 409, 429})
MAX_ASKED_DELAY_S = 60.0
FIRST_DELAY_S, MAX_DELAY_S = 0.5, 8.0


class ModelAPIError(Exception):
    """The endpoint failed or refused a completion; `status_code` is None when it was never
    reached (refused, reset, timed out)."""

    def __init__(self, message: str, status_code: int | None = None) -> None:
        super().__init__(message)
        self.status_code = status_code


@dataclass(frozen=True)
class Function:
    name: str
    arguments: str


@dataclass(frozen=True)
class ToolCall:
    id: str
    function: Function
    type: str = "function"


@dataclass(frozen=True)
class Message:
    """The assistant's reply: its text, and the tools it calls."""

    content: str | None = None
    tool_calls: list[ToolCall] = field(default_factory=list)
    role: str = "assistant"


@dataclass(frozen=True)
class Completion:
    message: Message | None  # None: the server answered with no choice (a filtered prompt)
    usage: dict[str, Any]  # as the server reported it ({} when it did not)


def message_of(data: Any) -> Message:
    """The reply a response's `choices[0].message` holds; ModelAPIError if it is malformed."""
    try:
        calls = [
            ToolCall(
                str(call["id"]),
                Function(str(call["function"]["name"]), str(call["function"]["arguments"])),
                str(call.get("type", "function")),
            )
            for call in data.get("tool_calls") or []
        ]
        content = data.get("content")
    except (AttributeError, KeyError, TypeError) as error:
        raise ModelAPIError(f"the model endpoint's answer is malformed: {error!r}") from None
    return Message(content if isinstance(content, str) else None, calls)


class ChatAPI:
    """`POST {base_url}/chat/completions`, with the SDK's retries (see module doc)."""

    def __init__(
        self, *, base_url: str | None, api_key: str, max_retries: int, timeout: float
    ) -> None:
        base = base_url or os.environ.get("OPENAI_BASE_URL") or DEFAULT_BASE_URL
        self.url = base.rstrip("/") + "/chat/completions"
        self.api_key = api_key
        self.max_retries = max_retries
        self.timeout = timeout

    def complete(self, body: dict[str, Any]) -> Completion:
        request = urllib.request.Request(
            self.url,
            data=json.dumps(body).encode(),
            headers={"Authorization": f"Bearer {self.api_key}", "Content-Type": "application/json"},
            method="POST",
        )
        for attempt in range(self.max_retries + 1):
            last = attempt == self.max_retries
            try:
                with urllib.request.urlopen(request, timeout=self.timeout) as response:
                    return completion_of(response.read())
            except urllib.error.HTTPError as error:
                if last or not should_retry(error.code, error.headers):
                    detail = error.read().decode("utf-8", "replace")[:500]
                    raise ModelAPIError(
                        f"Error code: {error.code} - {detail}", error.code
                    ) from None
                time.sleep(backoff(attempt, error.headers))
            except OSError as error:  # refused, reset, timed out (URLError is one of them)
                if last:
                    raise ModelAPIError(f"Connection error: {error}") from None
                time.sleep(backoff(attempt, None))
        raise AssertionError("unreachable: the last attempt returns or raises")


def completion_of(raw: bytes) -> Completion:
    try:
        data = json.loads(raw)
    except ValueError:
        raise ModelAPIError("the model endpoint answered without JSON") from None
    if not isinstance(data, dict):
        raise ModelAPIError("the model endpoint's answer is not a JSON object")
    choices = data.get("choices") or []
    message = message_of(choices[0].get("message") or {}) if choices else None
    usage = data.get("usage")
    return Completion(message, usage if isinstance(usage, dict) else {})


def should_retry(status: int, headers: Headers) -> bool:
    said = headers.get("x-should-retry")
    if said in ("true", "false"):
        return said == "true"
    return status in RETRIED_STATUSES or status >= 500


def backoff(attempt: int, headers: Headers | None) -> float:
    """Seconds before retry `attempt + 1`: what the server asked, else exponential with jitter."""
    asked = asked_delay(headers) if headers is not None else None
    if asked is not None and 0 <= asked <= MAX_ASKED_DELAY_S:
        return asked
    return min(FIRST_DELAY_S * 2**attempt, MAX_DELAY_S) * (1 - 0.25 * random.random())


def asked_delay(headers: Headers) -> float | None:
    try:
        if (milliseconds := headers.get("retry-after-ms")) is not None:
            return float(milliseconds) / 1000
        value = headers.get("retry-after")
        if value is None:
            return None
        try:
            return float(value)
        except ValueError:
            return parsedate_to_datetime(value).timestamp() - time.time()
    except (TypeError, ValueError, IndexError):
        return None

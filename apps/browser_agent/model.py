"""The model: any OpenAI-compatible chat-completions endpoint, and what it costs.

Every call — the agent loop's and wait_for's judge's — goes through `ChatModel.complete`,
which adds the response's token counts to a `CostLedger` and rewrites `costs.json` in the
task folder at once, atomically: an agent killed at its deadline still leaves its costs, in the
format `bench grade` reads (`model`, `input_tokens`, `output_tokens`, `tool_calls` at the top;
`cached_tokens`, `calls` and `per_model` beside them).

The token budget is enforced here too, before each call, so the judge cannot overspend it
either: once input + output tokens reach it, `BudgetExhausted` is raised instead of calling.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from apps.browser_agent.chat_api import ChatAPI, Completion, Message

COSTS_FILE = "costs.json"
DEFAULT_MAX_RETRIES = 6
DEFAULT_TIMEOUT_S = 180.0  # one completion; a local model on a CPU can take a while


class BudgetExhausted(Exception):
    """The task's token or wall-clock budget is spent: the agent stops (not a crash)."""


@dataclass
class Usage:
    input_tokens: int = 0
    output_tokens: int = 0
    cached_tokens: int = 0  # of input_tokens, served from the provider's prompt cache
    calls: int = 0
    tool_calls: int = 0

    @property
    def total_tokens(self) -> int:
        return self.input_tokens + self.output_tokens

    def add(self, other: Usage) -> None:
        self.input_tokens += other.input_tokens
        self.output_tokens += other.output_tokens
        self.cached_tokens += other.cached_tokens
        self.calls += other.calls
        self.tool_calls += other.tool_calls

    def minus(self, earlier: Usage) -> Usage:
        """What was spent since `earlier` (a copy of this ledger's total taken then)."""
        return Usage(
            self.input_tokens - earlier.input_tokens,
            self.output_tokens - earlier.output_tokens,
            self.cached_tokens - earlier.cached_tokens,
            self.calls - earlier.calls,
            self.tool_calls - earlier.tool_calls,
        )

    def copy(self) -> Usage:
        return Usage(**asdict(self))

    def as_json(self) -> dict[str, int]:
        """The two counts a transcript line keeps (README, "The task timeline")."""
        return {"input_tokens": self.input_tokens, "output_tokens": self.output_tokens}


def usage_of(response: Completion) -> Usage:
    """One response's tokens (0 when the server reports none) and the tool calls it made."""
    reported = response.usage
    details = reported.get("prompt_tokens_details") or {}
    return Usage(
        input_tokens=int(reported.get("prompt_tokens") or 0),
        output_tokens=int(reported.get("completion_tokens") or 0),
        cached_tokens=int(details.get("cached_tokens") or 0) if isinstance(details, dict) else 0,
        calls=1,
        tool_calls=len(response.message.tool_calls) if response.message else 0,
    )


class CostLedger:
    """Usage per model, written to `path` after every call (None: kept in memory only)."""

    def __init__(self, model: str, path: Path | None = None) -> None:
        self.model = model
        self.path = path
        self.per_model: dict[str, Usage] = {}

    @property
    def total(self) -> Usage:
        total = Usage()
        for usage in self.per_model.values():
            total.add(usage)
        return total

    def record(self, model: str, usage: Usage) -> None:
        self.per_model.setdefault(model, Usage()).add(usage)
        if self.path is not None:
            self.write()

    def as_json(self) -> dict[str, Any]:
        return {
            "model": self.model,
            **asdict(self.total),
            "per_model": {model: asdict(usage) for model, usage in self.per_model.items()},
        }

    def write(self) -> None:
        assert self.path is not None
        # A reader (the harness, after a kill) sees the old file or the new one, never half.
        handle, temporary = tempfile.mkstemp(dir=self.path.parent, prefix=".costs-", suffix=".tmp")
        with os.fdopen(handle, "w", encoding="utf-8") as file:
            json.dump(self.as_json(), file, indent=1)
        os.replace(temporary, self.path)


def make_client(
    *,
    base_url: str | None,
    api_key: str,
    max_retries: int = DEFAULT_MAX_RETRIES,
    timeout: float = DEFAULT_TIMEOUT_S,
) -> ChatAPI:
    # The client's own retries back off exponentially (honouring Retry-After) on 408, 409, 429,
    # 5xx and connection errors; they are all the retrying this agent does.
    return ChatAPI(base_url=base_url, api_key=api_key, max_retries=max_retries, timeout=timeout)


class ChatModel:
    """One model behind a client; every completion is accounted in `ledger`."""

    def __init__(
        self,
        client: ChatAPI,
        model: str,
        ledger: CostLedger,
        *,
        max_tokens_total: int | None = None,
    ) -> None:
        self.client = client
        self.model = model
        self.ledger = ledger
        self.max_tokens_total = max_tokens_total

    def complete(
        self, messages: list[dict[str, Any]], *, tools: list[dict[str, Any]] | None = None
    ) -> tuple[Message, Usage]:
        spent = self.ledger.total.total_tokens
        if self.max_tokens_total is not None and spent >= self.max_tokens_total:
            raise BudgetExhausted(
                f"token budget exhausted ({spent} of {self.max_tokens_total} tokens spent)"
            )
        body: dict[str, Any] = {"model": self.model, "messages": messages}
        if tools:
            body["tools"] = tools
        response = self.client.complete(body)
        usage = usage_of(response)
        self.ledger.record(self.model, usage)
        # Some servers answer a filtered prompt with no choice at all: an empty reply.
        return response.message or Message(), usage

"""A scripted OpenAI-compatible model server, for tests and demos (see README.md, "Scripts").

`POST /v1/chat/completions` answers from a script instead of a model; `GET /v1/models` lists
the script's model; `GET /v1/_stats` says what was served (requests, tokens, tool calls), so a
test can hold an agent's costs.json against it. Run it with

    python -m apps.browser_agent.scripted_model --script demo.yaml [--port 8765]

which prints its base URL (`http://127.0.0.1:8765/v1`) and serves until interrupted. A port
another program holds is refused with one line (exit 2). `--background` returns as soon as the
server listens, leaving it serving in its own session (its pid printed, to stop it), so a
shell script can chain the next command with `&&` and never start it against a server that is
not there.

Requests offering `tools` are the agent loop's: the turn is the number of assistant messages
already in the conversation, so a retried request gets the same answer and the server keeps no
state per conversation. Requests without `tools` are wait_for's judge questions
(`judging.judge_question`): the blocks after each `=== change N ===` line are the new changes; or
`bench grade --judge`'s (apps/bench/judge.py), whose lines after `=== report ===` are judged
(the same `judge.yes_when_any` rule: yes when a line holds one of its phrases).

Token counts are made up but plausible and deterministic: a token per 4 characters of text
(plus 4 per message), 765 per image, the prompt's stable prefix (everything before its last
user message, tool schemas included) counted as cached in steps of 128 once it reaches 1024, as
OpenAI's prompt cache does, and the reply's tokens from its text, tool name and arguments.
"""

from __future__ import annotations

import argparse
import errno
import json
import math
import os
import re
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

from apps.browser_agent.judging import JUDGE_CHANGE_PATTERN, REPORT_MARKER
from sentinel_site.yaml_files import YamlFileError, read_yaml

SCRIPT_KEYS = ("model", "agent", "judge", "failures")
REPLY_KEYS = ("call", "arguments", "text", "when_last_result", "otherwise")
JUDGE_KEYS = ("yes_when_any", "format")
FAILURE_KEYS = ("status", "retry_after_ms")
JUDGE_FORMATS = ("json", "text")
PLACEHOLDERS = {"{task_url}": "Task URL", "{contact_url}": "Contact URL"}
END_OF_SCRIPT = "The script has no more turns."
CHARS_PER_TOKEN = 4
MESSAGE_TOKENS = 4
IMAGE_TOKENS = 765
CACHE_MINIMUM, CACHE_STEP = 1024, 128
DEFAULT_RETRY_AFTER_MS = 10.0  # scripted failures ask the client to retry soon: tests stay fast


class ScriptError(ValueError):
    """A script the server cannot play: one line naming the file, the place and the problem."""


class RequestError(Exception):
    """A request the script cannot answer: sent back as an OpenAI-style error body."""

    def __init__(
        self,
        status: int,
        message: str,
        kind: str = "invalid_request_error",
        retry_after_ms: float | None = None,
    ) -> None:
        super().__init__(message)
        self.status = status
        self.kind = kind
        self.retry_after_ms = retry_after_ms


# --- the script --------------------------------------------------------------------------------


@dataclass(frozen=True)
class Reply:
    call: str | None  # a tool to call, or None for a reply of text only
    arguments: dict[str, Any]
    text: str | None
    when_last_result: str | None  # None: unconditional (a lone turn, or `otherwise`)


@dataclass(frozen=True)
class Turn:
    """One agent turn: a single reply, or alternatives chosen by the last tool result."""

    alternatives: tuple[Reply, ...]

    def choose(self, last_result: str) -> Reply:
        for reply in self.alternatives:
            wanted = reply.when_last_result
            if wanted is None or wanted.lower() in last_result.lower():
                return reply
        raise AssertionError("a parsed turn always ends with an unconditional reply")


@dataclass(frozen=True)
class JudgeRule:
    yes_when_any: tuple[str, ...] = ()
    format: str = "json"

    def answer(self, blocks: list[str]) -> str:
        """On wait_for's question: whether a line the changes added holds a needle."""
        added = [line[1:] for block in blocks for line in block.splitlines() if line[:1] == "+"]
        return self.answer_lines(added)

    def answer_lines(self, added: list[str]) -> str:
        found = next((n for n in self.yes_when_any if any(n in line for line in added)), None)
        met = found is not None
        if met:
            why = f"a new change mentions {found!r}"
        elif self.yes_when_any:
            why = f"no new change mentions {' or '.join(map(repr, self.yes_when_any))}"
        else:
            why = "this script's judge never says yes"
        if self.format == "text":
            return f"{'yes' if met else 'no'}: {why}"
        return json.dumps({"met": met, "why": why})


@dataclass(frozen=True)
class Failure:
    status: int
    retry_after_ms: float = DEFAULT_RETRY_AFTER_MS


@dataclass(frozen=True)
class Script:
    model: str
    turns: tuple[Turn, ...]
    judge: JudgeRule = field(default_factory=JudgeRule)
    failures: tuple[Failure, ...] = ()


def _mapping(value: Any, where: str, allowed: tuple[str, ...]) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise ScriptError(f"{where}: must be a mapping with keys {', '.join(allowed)}")
    unknown = sorted(set(map(str, value)) - set(allowed))
    if unknown:
        raise ScriptError(f"{where}.{unknown[0]}: unknown key; allowed: {', '.join(allowed)}")
    return value


def _string(value: Any, where: str) -> str:
    if not isinstance(value, str) or not value:
        raise ScriptError(f"{where}: must be a non-empty string, got {value!r}")
    return value


def _reply(data: Any, where: str) -> Reply:
    data = _mapping(data, where, REPLY_KEYS)
    if "otherwise" in data and data["otherwise"] is not True:
        raise ScriptError(f"{where}.otherwise: must be true, got {data['otherwise']!r}")
    if "otherwise" in data and "when_last_result" in data:
        raise ScriptError(f"{where}: has both when_last_result and otherwise; keep one")
    call = _string(data["call"], f"{where}.call") if "call" in data else None
    text = _string(data["text"], f"{where}.text") if "text" in data else None
    if call is None and text is None:
        raise ScriptError(f"{where}: needs `call` (a tool call) or `text` (a final answer)")
    arguments = data.get("arguments", {})
    if not isinstance(arguments, dict):
        raise ScriptError(f"{where}.arguments: must be a mapping, got {arguments!r}")
    if arguments and call is None:
        raise ScriptError(f"{where}.arguments: given without `call`")
    condition = data.get("when_last_result")
    if condition is not None:
        condition = _string(condition, f"{where}.when_last_result")
    return Reply(call, arguments, text, condition)


def _turns(data: Any, source: str) -> tuple[Turn, ...]:
    """Group the flat list: a run of `when_last_result` replies closed by `otherwise: true` is
    one turn; any other reply is a turn by itself."""
    if not isinstance(data, list):
        raise ScriptError(f"{source}: agent: must be a list of replies")
    turns: list[Turn] = []
    pending: list[Reply] = []
    opened_at = None
    for index, item in enumerate(data):
        where = f"{source}: agent[{index}]"
        reply = _reply(item, where)
        is_otherwise = "otherwise" in item  # a mapping: _reply checked it
        if reply.when_last_result is not None:
            if not pending:
                opened_at = index
            pending.append(reply)
        elif is_otherwise:
            if not pending:
                raise ScriptError(
                    f"{where}: `otherwise` without when_last_result replies before it"
                )
            turns.append(Turn((*pending, reply)))
            pending = []
        elif pending:
            raise ScriptError(
                f"{source}: agent[{opened_at}]: alternatives must end with an `otherwise: true` "
                f"reply before agent[{index}]"
            )
        else:
            turns.append(Turn((reply,)))
    if pending:
        raise ScriptError(
            f"{source}: agent[{opened_at}]: alternatives must end with an `otherwise: true` reply"
        )
    return tuple(turns)


def _judge(data: Any, source: str) -> JudgeRule:
    if data is None:
        return JudgeRule()
    data = _mapping(data, f"{source}: judge", JUDGE_KEYS)
    needles = data.get("yes_when_any", [])
    if not isinstance(needles, list) or not all(isinstance(n, str) and n for n in needles):
        raise ScriptError(f"{source}: judge.yes_when_any: must be a list of non-empty strings")
    answer_format = data.get("format", "json")
    if answer_format not in JUDGE_FORMATS:
        raise ScriptError(
            f"{source}: judge.format: must be one of {', '.join(JUDGE_FORMATS)}, "
            f"got {answer_format!r}"
        )
    return JudgeRule(tuple(needles), answer_format)


def _failures(data: Any, source: str) -> tuple[Failure, ...]:
    if data is None:
        return ()
    if not isinstance(data, list):
        raise ScriptError(f"{source}: failures: must be a list of {{status, retry_after_ms}}")
    failures = []
    for index, item in enumerate(data):
        where = f"{source}: failures[{index}]"
        item = _mapping(item, where, FAILURE_KEYS)
        status = item.get("status")
        if isinstance(status, bool) or not isinstance(status, int) or not 400 <= status <= 599:
            raise ScriptError(
                f"{where}.status: must be an HTTP error status 400-599, got {status!r}"
            )
        delay = item.get("retry_after_ms", DEFAULT_RETRY_AFTER_MS)
        if isinstance(delay, bool) or not isinstance(delay, (int, float)) or delay < 0:
            raise ScriptError(f"{where}.retry_after_ms: must be a number ≥ 0, got {delay!r}")
        failures.append(Failure(status, float(delay)))
    return tuple(failures)


def parse_script(data: Any, *, source: str = "script") -> Script:
    data = _mapping(data, source, SCRIPT_KEYS)
    if "agent" not in data:
        raise ScriptError(f"{source}: agent: is required (the list of the agent's replies)")
    return Script(
        model=_string(data.get("model", "scripted"), f"{source}: model"),
        turns=_turns(data["agent"], source),
        judge=_judge(data.get("judge"), source),
        failures=_failures(data.get("failures"), source),
    )


def load_script(path: str | Path) -> Script:
    """A script from a YAML (or JSON, which is YAML) file."""
    try:
        data = read_yaml(path, "script file")
    except YamlFileError as error:
        raise ScriptError(str(error)) from None
    return parse_script(data, source=str(path))


# --- answering -------------------------------------------------------------------------------


def _parts(message: dict[str, Any]) -> tuple[str, int]:
    """A message's text and its number of images."""
    content = message.get("content")
    texts, images = [], 0
    if isinstance(content, str):
        texts.append(content)
    elif isinstance(content, list):
        for part in content:
            if isinstance(part, dict) and part.get("type") == "text":
                texts.append(str(part.get("text", "")))
            elif isinstance(part, dict) and part.get("type") == "image_url":
                images += 1
    for call in message.get("tool_calls") or []:
        function = call.get("function", {}) if isinstance(call, dict) else {}
        texts += [str(function.get("name", "")), str(function.get("arguments", ""))]
    return "\n".join(texts), images


def _tokens(text: str) -> int:
    return math.ceil(len(text) / CHARS_PER_TOKEN)


def prompt_tokens(request: dict[str, Any]) -> tuple[int, int]:
    """(prompt tokens, of which cached) for a request."""
    messages = request["messages"]
    per_message = []
    for message in messages:
        text, images = _parts(message)
        per_message.append(MESSAGE_TOKENS + _tokens(text) + images * IMAGE_TOKENS)
    tools = _tokens(json.dumps(request["tools"])) if request.get("tools") else 0
    last_user = max((i for i, m in enumerate(messages) if m.get("role") == "user"), default=0)
    prefix = tools + sum(per_message[:last_user])
    cached = prefix // CACHE_STEP * CACHE_STEP if prefix >= CACHE_MINIMUM else 0
    return tools + sum(per_message), cached


def completion_tokens(message: dict[str, Any]) -> int:
    text, _ = _parts(message)
    return max(1, _tokens(text))


def _conversation_urls(messages: list[dict[str, Any]]) -> dict[str, str]:
    found = {}
    for message in messages:
        text, _ = _parts(message)
        for placeholder, label in PLACEHOLDERS.items():
            match = re.search(rf"^{label}: (\S+)", text, re.MULTILINE)
            if match and placeholder not in found:
                found[placeholder] = match.group(1)
    return found


def _fill(value: Any, urls: dict[str, str], where: str) -> Any:
    if isinstance(value, str):
        for placeholder, label in PLACEHOLDERS.items():
            if placeholder in value:
                if placeholder not in urls:
                    raise RequestError(
                        400, f"{where}: uses {placeholder} but no {label!r} line is in the request"
                    )
                value = value.replace(placeholder, urls[placeholder])
        return value
    if isinstance(value, dict):
        return {key: _fill(item, urls, where) for key, item in value.items()}
    if isinstance(value, list):
        return [_fill(item, urls, where) for item in value]
    return value


def agent_reply(script: Script, messages: list[dict[str, Any]]) -> dict[str, Any]:
    """The assistant message for an agent-loop request."""
    turn = sum(1 for m in messages if m.get("role") == "assistant")
    if turn >= len(script.turns):
        return {"role": "assistant", "content": END_OF_SCRIPT}
    last_result = next((_parts(m)[0] for m in reversed(messages) if m.get("role") == "tool"), "")
    reply = script.turns[turn].choose(last_result)
    urls = _conversation_urls(messages)
    where = f"turn {turn}"
    message: dict[str, Any] = {"role": "assistant", "content": _fill(reply.text, urls, where)}
    if reply.call is not None:
        arguments = _fill(reply.arguments, urls, where)
        message["tool_calls"] = [
            {
                "id": f"call_{turn}",
                "type": "function",
                "function": {"name": reply.call, "arguments": json.dumps(arguments)},
            }
        ]
    return message


def judge_reply(script: Script, messages: list[dict[str, Any]]) -> dict[str, Any]:
    question = next((_parts(m)[0] for m in reversed(messages) if m.get("role") == "user"), "")
    if REPORT_MARKER in question:  # bench grade --judge: the report is what is judged
        report = question.split(REPORT_MARKER, 1)[1].splitlines()
        return {"role": "assistant", "content": script.judge.answer_lines(report)}
    blocks = JUDGE_CHANGE_PATTERN.split(question)[1:]
    return {"role": "assistant", "content": script.judge.answer(blocks)}


# --- the server --------------------------------------------------------------------------------


@dataclass
class Served:
    """What the server answered so far (failed requests count only in `requests`/`failed`)."""

    requests: int = 0
    failed: int = 0
    agent_requests: int = 0
    judge_requests: int = 0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    cached_tokens: int = 0
    tool_calls: int = 0


class ScriptedModel:
    """The script and what was served; thread-safe (the HTTP server answers in threads)."""

    def __init__(self, script: Script) -> None:
        self.script = script
        self.served = Served()
        self._lock = threading.Lock()

    def stats(self) -> dict[str, int]:
        with self._lock:
            return dict(vars(self.served))

    def complete(self, request: Any) -> dict[str, Any]:
        with self._lock:
            self.served.requests += 1
            number = self.served.requests
            failure = (
                self.script.failures[number - 1] if number <= len(self.script.failures) else None
            )
            if failure is not None:
                self.served.failed += 1
        if failure is not None:
            raise RequestError(
                failure.status, f"scripted failure {number}", "server_error", failure.retry_after_ms
            )
        try:
            response = self._answer(request, number)
        except RequestError:
            with self._lock:
                self.served.failed += 1
            raise
        return response

    def _answer(self, request: Any, number: int) -> dict[str, Any]:
        if not isinstance(request, dict) or not isinstance(request.get("messages"), list):
            raise RequestError(400, "the body must be a JSON object with a `messages` list")
        if request.get("model") != self.script.model:
            raise RequestError(
                404,
                f"model {request.get('model')!r} not found; this server serves "
                f"{self.script.model!r}",
                "model_not_found",
            )
        if request.get("stream"):
            raise RequestError(400, "streaming is not supported by the scripted model")
        is_agent = bool(request.get("tools"))
        messages = request["messages"]
        message = (agent_reply if is_agent else judge_reply)(self.script, messages)
        prompt, cached = prompt_tokens(request)
        completion = completion_tokens(message)
        calls = len(message.get("tool_calls", []))
        with self._lock:
            served = self.served
            served.agent_requests += is_agent
            served.judge_requests += not is_agent
            served.prompt_tokens += prompt
            served.completion_tokens += completion
            served.cached_tokens += cached
            served.tool_calls += calls
        return {
            "id": f"chatcmpl-scripted-{number}",
            "object": "chat.completion",
            "created": int(time.time()),
            "model": self.script.model,
            "choices": [
                {
                    "index": 0,
                    "message": message,
                    "finish_reason": "tool_calls" if calls else "stop",
                    "logprobs": None,
                }
            ],
            "usage": {
                "prompt_tokens": prompt,
                "completion_tokens": completion,
                "total_tokens": prompt + completion,
                "prompt_tokens_details": {"cached_tokens": cached},
            },
        }


class _Handler(BaseHTTPRequestHandler):
    server: _Server

    def log_message(self, format: str, *args: Any) -> None:
        pass  # quiet: a test's output is its own

    def do_GET(self) -> None:
        model = self.server.model
        if self.path.rstrip("/") == "/v1/models":
            entry = {
                "id": model.script.model,
                "object": "model",
                "created": 0,
                "owned_by": "scripted",
            }
            self._send(200, {"object": "list", "data": [entry]})
        elif self.path.rstrip("/") == "/v1/_stats":
            self._send(200, model.stats())
        else:
            self._error(RequestError(404, f"no route GET {self.path}"))

    def do_POST(self) -> None:
        if self.path.rstrip("/") != "/v1/chat/completions":
            self._error(RequestError(404, f"no route POST {self.path}"))
            return
        length = int(self.headers.get("Content-Length") or 0)
        try:
            request = json.loads(self.rfile.read(length) or b"null")
        except (json.JSONDecodeError, UnicodeDecodeError):
            self._error(RequestError(400, "the body is not JSON"))
            return
        try:
            self._send(200, self.server.model.complete(request))
        except RequestError as error:
            self._error(error)

    def _error(self, error: RequestError) -> None:
        body = {"error": {"message": str(error), "type": error.kind, "code": error.status}}
        headers = {}
        if error.retry_after_ms is not None:
            headers["retry-after-ms"] = f"{error.retry_after_ms:g}"
        self._send(error.status, body, headers)

    def _send(self, status: int, body: Any, headers: dict[str, str] | None = None) -> None:
        data = json.dumps(body).encode()
        self.send_response(status, HTTPStatus(status).phrase)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(data)))
        for name, value in (headers or {}).items():
            self.send_header(name, value)
        self.end_headers()
        self.wfile.write(data)


class _Server(ThreadingHTTPServer):
    daemon_threads = True

    def __init__(self, model: ScriptedModel, host: str, port: int) -> None:
        super().__init__((host, port), _Handler)
        self.model = model
        self.host = host

    @property
    def base_url(self) -> str:
        return f"http://{self.host}:{self.server_port}/v1"  # the port bound (0 asks for a free one)


@contextmanager
def scripted_model_server(script: Script, *, host: str = "127.0.0.1") -> Iterator[_Server]:
    """The server on a free port in a background thread; `.base_url`, `.model.stats()`."""
    server = _Server(ScriptedModel(script), host, 0)
    thread = threading.Thread(
        target=server.serve_forever,
        kwargs={"poll_interval": 0.05},
        name="scripted-model",
        daemon=True,
    )
    thread.start()
    try:
        yield server
    finally:
        server.shutdown()
        server.server_close()
        thread.join(timeout=5)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m apps.browser_agent.scripted_model", description=__doc__.splitlines()[0]
    )
    parser.add_argument("--script", required=True, type=Path, help="a YAML or JSON script")
    parser.add_argument("--port", type=int, default=0, help="default: a free port")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument(
        "--background",
        action="store_true",
        help="return once listening; the server goes on serving in its own session",
    )
    args = parser.parse_args(argv)
    try:
        script = load_script(args.script)
        server = _Server(ScriptedModel(script), args.host, args.port)
    except ScriptError as error:
        print(f"scripted_model: error: {error}", file=sys.stderr)
        return 2
    except OSError as error:
        taken = " (another program holds it: stop it or pick another --port)"
        print(
            f"scripted_model: error: cannot listen on {args.host}:{args.port}: {error.strerror}"
            + (taken if error.errno == errno.EADDRINUSE else ""),
            file=sys.stderr,
        )
        return 2
    if args.background and _detach():
        # The parent: the socket was bound before the fork, so the server is there already.
        print(f"{server.base_url} (pid {_child_pid}; stop it with: kill {_child_pid})", flush=True)
        server.server_close()
        return 0
    if not args.background:
        print(server.base_url, flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
    return 0


_child_pid = 0


def _detach() -> bool:
    """Fork; True in the parent. The child leaves the terminal's session and its output."""
    global _child_pid
    sys.stdout.flush()
    pid = os.fork()
    if pid:
        _child_pid = pid
        return True
    os.setsid()
    devnull = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(devnull, fd)
    return False


if __name__ == "__main__":
    sys.exit(main())

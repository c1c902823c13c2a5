"""The agent's chat-completions client (apps/browser_agent/chat_api.py): what it reads of an
answer, and when and how long it waits before trying again, as the OpenAI SDK does."""

from __future__ import annotations

import email.utils
import time
from email.message import Message as Headers

import pytest

from apps.browser_agent.chat_api import (
    Function,
    ModelAPIError,
    ToolCall,
    backoff,
    completion_of,
    should_retry,
)
from apps.browser_agent.model import CostLedger
from tests.browser_agent.conftest import served
from tests.browser_agent.test_model import ASK, SCRIPT, TOOLS, chat_model


def headers(**values: str) -> Headers:
    message = Headers()
    for name, value in values.items():
        message[name.replace("_", "-")] = value
    return message


def test_an_answer_gives_its_text_tool_calls_and_usage():
    answer = completion_of(
        b'{"choices": [{"message": {"role": "assistant", "content": null, "tool_calls": '
        b'[{"id": "c1", "type": "function", "function": {"name": "click", "arguments": "{}"}}]}}],'
        b' "usage": {"prompt_tokens": 12, "completion_tokens": 3}}'
    )
    assert answer.message is not None and answer.message.content is None
    assert answer.message.tool_calls == [ToolCall("c1", Function("click", "{}"))]
    assert answer.usage == {"prompt_tokens": 12, "completion_tokens": 3}
    assert completion_of(b'{"choices": []}').message is None  # a filtered prompt: no choice


@pytest.mark.parametrize(
    ("raw", "problem"),
    [
        (b"<html>gateway</html>", "without JSON"),
        (b"[1, 2]", "not a JSON object"),
        (b'{"choices": [{"message": {"tool_calls": [{"id": "c1"}]}}]}', "malformed"),
    ],
)
def test_an_answer_that_is_not_a_completion_is_a_clear_error(raw, problem):
    with pytest.raises(ModelAPIError, match=problem):
        completion_of(raw)


@pytest.mark.parametrize(
    ("status", "said", "retried"),
    [(408, None, True), (409, None, True), (429, None, True), (500, None, True),
     (503, None, True), (400, None, False), (404, None, False), (429, "false", False),
     (400, "true", True)],
)  # fmt: skip
def test_which_failures_are_tried_again(status, said, retried):
    assert should_retry(status, headers(**({"x_should_retry": said} if said else {}))) is retried


def test_the_wait_is_what_the_server_asks_else_doubling_with_jitter():
    assert backoff(0, headers(retry_after_ms="250")) == 0.25
    assert backoff(3, headers(retry_after="2")) == 2.0
    later = email.utils.formatdate(time.time() + 30, usegmt=True)
    assert 28.0 < backoff(0, headers(retry_after=later)) <= 30.0
    for attempt, ceiling in [(0, 0.5), (1, 1.0), (2, 2.0), (5, 8.0), (9, 8.0)]:
        for asked in (None, headers(retry_after="3600"), headers(retry_after="soon")):
            assert 0.75 * ceiling <= backoff(attempt, asked) <= ceiling


def test_a_refused_request_is_not_tried_again(scripted_model):
    server = scripted_model({**SCRIPT, "failures": [{"status": 400}]})
    with pytest.raises(ModelAPIError, match="Error code: 400") as failed:
        chat_model(server, CostLedger("scripted-1")).complete(ASK, tools=TOOLS)
    assert failed.value.status_code == 400
    assert served(server.base_url)["requests"] == 1

"""The scripted model server, spoken to through the real `openai` client."""

from __future__ import annotations

import importlib
import json
import subprocess
import sys
from typing import TYPE_CHECKING

import pytest

from apps.browser_agent.judging import judge_question
from apps.browser_agent.scripted_model import (
    END_OF_SCRIPT,
    IMAGE_TOKENS,
    ScriptError,
    load_script,
    parse_script,
)
from tests.browser_agent.conftest import REPO, served

if TYPE_CHECKING:
    import openai


def sdk():
    """The `openai` package, imported by the tests that use it: importing it takes seconds of
    CPU, which every test process would otherwise pay to collect this module."""
    return importlib.import_module("openai")


TASK_URL = "http://site.test/r/abc/start"
CONTACT_URL = "http://site.test/r/abc/contact"
TOOLS = [{"type": "function", "function": {"name": "wait_for", "parameters": {"type": "object"}}}]

DANA = {
    "model": "scripted-1",
    "agent": [
        {
            "call": "wait_for",
            "arguments": {"condition": "an email from Dana Whitfield arrives", "timeout": 150},
        },
        {
            "when_last_result": "met: true",
            "call": "contact",
            "arguments": {"message": "Dana's email has arrived; see {task_url}"},
        },
        {"otherwise": True, "call": "terminate", "arguments": {"reason": "it never came"}},
        {"text": "Reported to {contact_url}."},
    ],
    "judge": {"yes_when_any": ["Dana"]},
}


def client(server, **options) -> openai.OpenAI:
    return sdk().OpenAI(base_url=server.base_url, api_key="not-needed", **options)


def conversation(*results: str) -> list[dict]:
    """The agent's messages after one tool call per result."""
    messages = [
        {"role": "system", "content": "You are a web agent."},
        {"role": "user", "content": f"Task URL: {TASK_URL}\nContact URL: {CONTACT_URL}\n\nGo."},
    ]
    for turn, result in enumerate(results):
        call = {
            "id": f"call_{turn}",
            "type": "function",
            "function": {"name": "x", "arguments": "{}"},
        }
        messages += [
            {"role": "assistant", "content": None, "tool_calls": [call]},
            {"role": "tool", "tool_call_id": f"call_{turn}", "content": result},
        ]
    return messages


def ask(server, messages: list[dict], *, tools=TOOLS):
    options = {"tools": tools} if tools else {}
    return client(server).chat.completions.create(model="scripted-1", messages=messages, **options)


def test_the_first_turn_is_the_scripts_first_tool_call(scripted_model):
    server = scripted_model(DANA)
    response = ask(server, conversation())
    call = response.choices[0].message.tool_calls[0]
    assert call.function.name == "wait_for"
    assert json.loads(call.function.arguments) == {
        "condition": "an email from Dana Whitfield arrives",
        "timeout": 150,
    }
    assert response.choices[0].finish_reason == "tool_calls"


@pytest.mark.parametrize(
    ("last_result", "tool", "arguments"),
    [
        ("met: true — a new change mentions 'Dana'", "contact", {"message": f"Dana's email has arrived; see {TASK_URL}"}),
        ("MET: TRUE — case does not matter", "contact", {"message": f"Dana's email has arrived; see {TASK_URL}"}),
        ("met: false — no changes detected before the timeout", "terminate", {"reason": "it never came"}),
    ],
)  # fmt: skip
def test_alternatives_are_chosen_by_the_last_tool_result(
    scripted_model, last_result, tool, arguments
):
    server = scripted_model(DANA)
    call = ask(server, conversation(last_result)).choices[0].message.tool_calls[0]
    assert (call.function.name, json.loads(call.function.arguments)) == (tool, arguments)


def test_a_text_turn_and_the_end_of_the_script_call_no_tool(scripted_model):
    server = scripted_model(DANA)
    final = ask(server, conversation("met: true", "contacted")).choices[0]
    assert final.message.content == f"Reported to {CONTACT_URL}."
    assert final.message.tool_calls is None
    assert final.finish_reason == "stop"
    after = ask(server, conversation("met: true", "contacted", "?")).choices[0].message
    assert (after.content, after.tool_calls) == (END_OF_SCRIPT, None)


def test_a_placeholder_without_its_url_in_the_conversation_is_a_one_line_400(scripted_model):
    server = scripted_model({"agent": [{"call": "visit_url", "arguments": {"url": "{task_url}"}}]})
    with pytest.raises(sdk().BadRequestError) as error:
        client(server).chat.completions.create(
            model="scripted", messages=[{"role": "user", "content": "Go."}], tools=TOOLS
        )
    assert "turn 0: uses {task_url} but no 'Task URL' line is in the request" in str(error.value)


@pytest.mark.parametrize(
    ("rule", "block", "answer"),
    [
        ({"yes_when_any": ["Dana"]}, "+ Dana Whitfield — Offsite plan", {"met": True, "why": "a new change mentions 'Dana'"}),
        # Context and removed lines are not news: only added lines count.
        ({"yes_when_any": ["Dana"]}, "  Dana Whitfield — old\n+ Kevin Lee — Expenses", {"met": False, "why": "no new change mentions 'Dana'"}),
        ({}, "+ Dana Whitfield", {"met": False, "why": "this script's judge never says yes"}),
    ],
)  # fmt: skip
def test_the_judge_says_yes_when_an_added_line_mentions_a_keyword(
    scripted_model, rule, block, answer
):
    server = scripted_model({**DANA, "judge": rule})
    # The condition names Dana too: only the changes are searched.
    question = judge_question("an email from Dana Whitfield arrives", [block])
    response = ask(server, [{"role": "user", "content": question}], tools=None)
    assert json.loads(response.choices[0].message.content) == answer


def test_the_judge_can_answer_in_words(scripted_model):
    server = scripted_model({**DANA, "judge": {"yes_when_any": ["Dana"], "format": "text"}})
    question = judge_question("Dana writes", ["+ Dana Whitfield"])
    response = ask(server, [{"role": "user", "content": question}], tools=None)
    assert response.choices[0].message.content == "yes: a new change mentions 'Dana'"


def test_usage_is_deterministic_and_an_image_costs_a_fixed_amount(scripted_model):
    server = scripted_model(DANA)
    first = ask(server, conversation()).usage
    again = ask(server, conversation()).usage
    assert first == again
    assert first.prompt_tokens > 0 and first.completion_tokens > 0
    with_image = conversation()
    with_image.append(
        {
            "role": "user",
            "content": [
                {"type": "text", "text": ""},
                {"type": "image_url", "image_url": {"url": "data:image/png;base64,AAAA"}},
            ],
        }
    )
    usage = ask(server, with_image).usage
    # One more message (4 tokens) and its image.
    assert usage.prompt_tokens == first.prompt_tokens + 4 + IMAGE_TOKENS


def test_a_long_stable_prefix_is_reported_as_cached(scripted_model):
    server = scripted_model(DANA)
    short = ask(server, conversation()).usage
    assert short.prompt_tokens_details.cached_tokens == 0
    long = conversation()
    long[0]["content"] = "x" * 8000  # 2000 tokens of system prompt before the last user message
    usage = ask(server, long).usage
    cached = usage.prompt_tokens_details.cached_tokens
    assert cached >= 1024 and cached % 128 == 0 and cached < usage.prompt_tokens


def test_stats_count_what_was_served(scripted_model):
    server = scripted_model(DANA)
    agent = ask(server, conversation()).usage
    judge = ask(server, [{"role": "user", "content": judge_question("c", ["+ x"])}], tools=None)
    assert served(server.base_url) == {
        "requests": 2,
        "failed": 0,
        "agent_requests": 1,
        "judge_requests": 1,
        "prompt_tokens": agent.prompt_tokens + judge.usage.prompt_tokens,
        "completion_tokens": agent.completion_tokens + judge.usage.completion_tokens,
        "cached_tokens": 0,
        "tool_calls": 1,
    }


def test_it_lists_its_model_and_refuses_others(scripted_model):
    server = scripted_model(DANA)
    assert [m.id for m in client(server).models.list()] == ["scripted-1"]
    with pytest.raises(sdk().NotFoundError, match="model 'gpt-4o' not found"):
        client(server).chat.completions.create(model="gpt-4o", messages=[], tools=TOOLS)


@pytest.mark.parametrize(
    ("script", "message"),
    [
        ({"agent": [], "colour": 1}, "script.colour: unknown key; allowed: model, agent, judge, failures"),
        ({"model": "m"}, "script: agent: is required (the list of the agent's replies)"),
        ({"agent": [{"arguments": {"a": 1}}]}, "script: agent[0]: needs `call` (a tool call) or `text` (a final answer)"),
        ({"agent": [{"call": "x", "wait": 3}]}, "script: agent[0].wait: unknown key; allowed: call, arguments, text, when_last_result, otherwise"),
        ({"agent": [{"when_last_result": "met", "call": "x"}, {"call": "y"}]}, "script: agent[0]: alternatives must end with an `otherwise: true` reply before agent[1]"),
        ({"agent": [{"when_last_result": "met", "call": "x"}]}, "script: agent[0]: alternatives must end with an `otherwise: true` reply"),
        ({"agent": [{"otherwise": True, "call": "x"}]}, "script: agent[0]: `otherwise` without when_last_result replies before it"),
        ({"agent": [], "judge": {"format": "xml"}}, "script: judge.format: must be one of json, text, got 'xml'"),
        ({"agent": [], "failures": [{"status": 200}]}, "script: failures[0].status: must be an HTTP error status 400-599, got 200"),
    ],
)  # fmt: skip
def test_a_bad_script_is_one_line_naming_the_place(script, message):
    with pytest.raises(ScriptError) as error:
        parse_script(script)
    assert str(error.value) == message


def test_a_yaml_script_with_a_syntax_error_names_the_line(tmp_path):
    path = tmp_path / "s.yaml"
    path.write_text("agent:\n  - call: [wait_for\n")
    with pytest.raises(ScriptError, match=r"s\.yaml: invalid YAML at line 3, column 1"):
        load_script(path)


def run_cli(*args: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "apps.browser_agent.scripted_model", *args],
        cwd=REPO,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def test_the_command_prints_its_base_url_and_serves_the_script(tmp_path):
    path = tmp_path / "demo.yaml"
    path.write_text("model: scripted-1\nagent:\n  - call: read_page\n")
    process = run_cli("--script", str(path))
    try:
        base_url = process.stdout.readline().strip()
        assert base_url.startswith("http://127.0.0.1:") and base_url.endswith("/v1")
        reply = (
            sdk()
            .OpenAI(base_url=base_url, api_key="x")
            .chat.completions.create(
                model="scripted-1", messages=[{"role": "user", "content": "Go."}], tools=TOOLS
            )
        )
        assert reply.choices[0].message.tool_calls[0].function.name == "read_page"
    finally:
        process.terminate()
        process.wait(timeout=10)


def test_the_command_rejects_a_bad_script_in_one_line(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text("agent: {call: x}\n")
    process = run_cli("--script", str(path))
    _, stderr = process.communicate(timeout=20)
    assert process.returncode == 2
    assert stderr == f"scripted_model: error: {path}: agent: must be a list of replies\n"

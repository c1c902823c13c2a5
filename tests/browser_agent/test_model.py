"""The model client: retries, usage accounting, costs.json, the token budget and the judge."""

from __future__ import annotations

import json

import pytest

from apps.browser_agent.chat_api import ModelAPIError
from apps.browser_agent.judging import parse_judge_answer
from apps.browser_agent.model import BudgetExhausted, ChatModel, CostLedger, make_client
from apps.browser_agent.tools import ModelJudge
from tests.browser_agent.conftest import served

TOOLS = [{"type": "function", "function": {"name": "read_page", "parameters": {"type": "object"}}}]
SCRIPT = {
    "model": "scripted-1",
    "agent": [{"call": "read_page"}, {"text": "Done."}],
    "judge": {"yes_when_any": ["Kevin Lee"]},
}
ASK = [{"role": "user", "content": "Task URL: http://site.test/\n\nRead the page."}]


def chat_model(server, ledger: CostLedger, **options) -> ChatModel:
    retries = options.pop("max_retries", 3)
    client = make_client(base_url=server.base_url, api_key="not-needed", max_retries=retries)
    return ChatModel(client, "scripted-1", ledger, **options)


def test_a_429_and_a_500_are_retried_then_the_answer_counts_once(scripted_model):
    server = scripted_model({**SCRIPT, "failures": [{"status": 429}, {"status": 500}]})
    ledger = CostLedger("scripted-1")
    message, usage = chat_model(server, ledger).complete(ASK, tools=TOOLS)
    assert message.tool_calls[0].function.name == "read_page"
    stats = served(server.base_url)
    assert (stats["requests"], stats["failed"]) == (3, 2)
    assert ledger.total.calls == 1
    assert usage.input_tokens == stats["prompt_tokens"]


def test_failures_beyond_the_retries_reach_the_caller(scripted_model):
    server = scripted_model({**SCRIPT, "failures": [{"status": 503}] * 3})
    ledger = CostLedger("scripted-1")
    with pytest.raises(ModelAPIError, match="Error code: 503") as failed:
        chat_model(server, ledger, max_retries=1).complete(ASK, tools=TOOLS)
    assert failed.value.status_code == 503
    assert served(server.base_url)["requests"] == 2
    assert ledger.total.calls == 0


def test_usage_accumulates_and_costs_json_is_rewritten_after_every_call(scripted_model, tmp_path):
    server = scripted_model(SCRIPT)
    costs = tmp_path / "costs.json"
    ledger = CostLedger("scripted-1", costs)
    model = chat_model(server, ledger)

    model.complete(ASK, tools=TOOLS)
    after_one = json.loads(costs.read_text())
    assert (after_one["calls"], after_one["tool_calls"]) == (1, 1)

    answer = {"role": "assistant", "content": None, "tool_calls": [_call("read_page")]}
    model.complete([*ASK, answer, _result("# Inbox")], tools=TOOLS)
    ModelJudge(model)("Kevin Lee writes", ["+ Kevin Lee — Expenses"])

    stats = served(server.base_url)
    written = json.loads(costs.read_text())
    totals = {
        "input_tokens": stats["prompt_tokens"],
        "output_tokens": stats["completion_tokens"],
        "cached_tokens": stats["cached_tokens"],
        "calls": 3,
        "tool_calls": 1,
    }
    assert written == {"model": "scripted-1", **totals, "per_model": {"scripted-1": totals}}
    assert not list(tmp_path.glob(".costs-*"))  # the atomic write leaves no temporary file


def test_the_token_budget_stops_before_the_call_that_would_exceed_it(scripted_model):
    server = scripted_model(SCRIPT)
    ledger = CostLedger("scripted-1")
    model = chat_model(server, ledger, max_tokens_total=10)
    model.complete(ASK, tools=TOOLS)  # the budget is checked before a call, not during it
    spent = ledger.total.total_tokens
    with pytest.raises(BudgetExhausted, match=rf"token budget exhausted \({spent} of 10 tokens"):
        model.complete(ASK, tools=TOOLS)
    assert served(server.base_url)["requests"] == 1


def test_the_judge_asks_without_tools_and_reads_the_answer(scripted_model):
    server = scripted_model(SCRIPT)
    judge = ModelJudge(chat_model(server, CostLedger("scripted-1")))
    assert judge("an email from Kevin Lee", ["  Inbox\n+ Kevin Lee — Expenses"]) == (
        True,
        "a new change mentions 'Kevin Lee'",
    )
    assert judge("an email from Kevin Lee", ["+ Maya Okonjo — Agenda"])[0] is False
    assert served(server.base_url)["judge_requests"] == 2


@pytest.mark.parametrize(
    ("answer", "verdict"),
    [
        ('{"met": true, "why": "Kevin wrote"}', (True, "Kevin wrote")),
        ('```json\n{"met": false, "why": "only the clock moved"}\n```', (False, "only the clock moved")),
        ("Yes: the email from Kevin Lee is there.", (True, "the email from Kevin Lee is there.")),
        ("no - nothing new", (False, "nothing new")),
        ("Perhaps.", (False, "the judge's answer was neither yes nor no: 'Perhaps.'")),
    ],
)  # fmt: skip
def test_judge_answers_are_read_as_json_or_yes_no(answer, verdict):
    assert parse_judge_answer(answer) == verdict


def _call(name: str) -> dict:
    return {"id": "call_0", "type": "function", "function": {"name": name, "arguments": "{}"}}


def _result(text: str) -> dict:
    return {"role": "tool", "tool_call_id": "call_0", "content": text}

"""Whether the agent's report says what it must: the contact message judged against the
scenario's `contact_rubric` (optional; the paper grades a contact by its time only, so "done"
passed as well as a report naming what happened).

A rubric is `{"rubric": "what a good report says", "must_mention": ["Kevin Lee", …]}` (either
or both). `bench grade --judge MODEL` asks an OpenAI-compatible model (`--judge-url`, as the
reference agents' `--model-url`) whether the message meets the rubric; without a model the
deterministic keyword rule judges instead: every `must_mention` phrase appears in the message
(case-insensitive). The judgement, who made it and the exact prompt are kept beside the task's
results (`judgement.json`), so a published figure can be audited and re-judged.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from apps.browser_agent.judging import REPORT_MARKER, judge_verdict  # (the report follows it)

JUDGEMENT = "judgement.json"
# A question is idempotent: a rate limit or a dropped connection is asked again, a wrong URL
# fails within seconds (the agents' own clients retry far longer).
JUDGE_RETRIES = 2
KEYWORDS = "keywords"  # `by` of a judgement the keyword rule made

Ask = Callable[[str], str]  # a judge prompt → the model's answer


class JudgeError(RuntimeError):
    """The judge model could not be asked or gave no usable answer; the message says which."""


@dataclass(frozen=True)
class Judgement:
    correct: bool
    why: str
    by: str  # KEYWORDS, or the judge model's name
    prompt: str = ""  # what the model was asked (empty for the keyword rule)
    answer: str = ""  # what it answered

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


def by_keywords(rubric: dict[str, Any], message: str) -> Judgement:
    """Every `must_mention` phrase in the message, case-insensitive, spaces collapsed."""

    def plain(text: str) -> str:
        return " ".join(text.lower().split())

    said = plain(message)
    missing = [p for p in rubric.get("must_mention", []) if plain(p) not in said]
    why = f"does not mention {', '.join(map(repr, missing))}" if missing else "mentions all"
    return Judgement(correct=not missing, why=why, by=KEYWORDS)


def judge_prompt(task_prompt: str, rubric: dict[str, Any], message: str) -> str:
    must = rubric.get("must_mention") or []
    lines = [
        "You judge a monitoring agent's report to its user: does it say what it must?",
        f"The agent's task: {task_prompt}" if task_prompt else "",
        f"What a correct report must say: {rubric.get('rubric', '').strip()}"
        if rubric.get("rubric")
        else "",
        f"It must mention: {'; '.join(must)}" if must else "",
        'Answer with JSON only: {"correct": true or false, "why": "one sentence"}.',
        REPORT_MARKER,
        message,
    ]
    return "\n".join(line for line in lines if line)


def read_answer(answer: str) -> tuple[bool, str]:
    """(correct, why) from a judge's answer: JSON {"correct"|"met": bool, "why"}, or text
    starting yes/no. JudgeError when it is neither: no verdict is made up for the agent."""
    verdict = judge_verdict(answer, keys=("correct", "met"))
    if verdict is None:
        raise JudgeError(
            f"the judge's answer is neither JSON with 'correct' nor yes/no: {answer!r}"
        )
    return verdict


def by_model(ask: Ask, model: str, task_prompt: str, rubric: dict[str, Any], message: str):
    prompt = judge_prompt(task_prompt, rubric, message)
    answer = ask(prompt)
    correct, why = read_answer(answer)
    return Judgement(correct=correct, why=why, by=model, prompt=prompt, answer=answer)


def model_asker(model: str, base_url: str | None, api_key: str) -> Ask:
    """A question to `model` behind an OpenAI-compatible endpoint, its answer's text."""
    from apps.browser_agent.chat_api import ModelAPIError
    from apps.browser_agent.model import make_client

    client = make_client(base_url=base_url, api_key=api_key, max_retries=JUDGE_RETRIES)

    def ask(prompt: str) -> str:
        body = {"model": model, "messages": [{"role": "user", "content": prompt}]}
        try:
            reply = client.complete(body).message
        except ModelAPIError as error:
            raise JudgeError(f"the judge model {model!r} could not be asked: {error}") from None
        if reply is None or not reply.content:
            raise JudgeError(f"the judge model {model!r} gave an empty answer")
        return reply.content

    return ask


def judge_result(
    result: dict[str, Any], folder: Path | None, ask: Ask | None, model: str
) -> Judgement | None:
    """The judgement of one task's report (None: no rubric, or no message to judge), written
    to `folder`/judgement.json when there is one."""
    rubric = result.get("contact_rubric")
    message = result.get("contact_message")
    if not rubric or message is None:
        return None
    if ask is not None:
        judgement = by_model(ask, model, str(result.get("prompt") or ""), rubric, message)
    elif rubric.get("must_mention"):
        judgement = by_keywords(rubric, message)
    else:
        return None  # a rubric only a model can apply, and no model
    if folder is not None:
        (folder / JUDGEMENT).write_text(json.dumps(judgement.as_dict(), indent=2) + "\n")
    return judgement

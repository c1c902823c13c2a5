"""The judge's questions and answers, in words: what wait_for asks its model about a page's
changes, what `bench grade --judge` asks about a report, and how an answer is read.

Apart from the tools (and their browser and model client) because the grading reads them too,
and a process that only grades must not import Playwright and OpenAI to do so.
"""

from __future__ import annotations

import json
import re

JUDGE_CHANGE_CHARS = 8000  # diff text in one judge question: a page rewritten whole is cut
JUDGE_PROMPT = (
    "You watch a web page for someone waiting for a condition. You are shown the condition and "
    "the parts of the page that changed since they started waiting, as unified-diff blocks "
    "(lines starting with '+' appeared, '-' disappeared, ' ' are unchanged context). Decide "
    "whether these changes show that the condition now holds. Answer with JSON only: "
    '{"met": true or false, "why": "one short sentence"}.'
)
# Each block of a judge question starts with this header line (scripted_model reads them).
JUDGE_CHANGE_HEADER = "=== change {number} ==="
JUDGE_CHANGE_PATTERN = re.compile(r"^=== change \d+ ===$", re.MULTILINE)
# In `bench grade --judge`'s question (apps/bench/judge.py), the agent's report follows this line.
REPORT_MARKER = "=== report ==="


def judge_question(condition: str, blocks: list[str]) -> str:
    changes, room = [], JUDGE_CHANGE_CHARS
    for number, block in enumerate(blocks, start=1):
        if room <= 0:
            changes.append(f"({len(blocks) - number + 1} more changes not shown)")
            break
        changes += [JUDGE_CHANGE_HEADER.format(number=number), block[:room]]
        room -= len(block)
    return "\n".join([f"Condition: {condition}", "", "Changes:", *changes])


_YES_NO = re.compile(r"^\W*(yes|no)\b\W*(.*)", re.IGNORECASE | re.DOTALL)


def judge_verdict(text: str, keys: tuple[str, ...] = ("met",)) -> tuple[bool, str] | None:
    """A judge's verdict and reason: its JSON `{<key>: bool, "why"}` (the first of `keys` it
    has; also inside a code fence), or "yes/no: why"; None when the answer is neither."""
    found = re.search(r"\{.*\}", text, re.DOTALL)
    if found:
        try:
            answer = json.loads(found.group(0))
        except json.JSONDecodeError:
            answer = None
        if isinstance(answer, dict):
            verdict = next((answer[k] for k in keys if isinstance(answer.get(k), bool)), None)
            if verdict is not None:
                return verdict, str(answer.get("why") or "").strip()
    plain = _YES_NO.match(text.strip())
    if plain:
        return plain.group(1).lower() == "yes", plain.group(2).strip()
    return None


def parse_judge_answer(text: str) -> tuple[bool, str]:
    """wait_for's reading of its judge: an answer that is neither JSON nor yes/no counts as not
    met, so a confused judge keeps the agent waiting."""
    return judge_verdict(text) or (
        False,
        f"the judge's answer was neither yes nor no: {text.strip()[:200]!r}",
    )

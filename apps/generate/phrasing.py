"""The same request in other words: a template's prompt rephrased, meaning kept.

Only wording that never carries the task's condition is touched — how the user asks to be told
("tell me" / "let me know" / "ping me"), how they ask to be watched for ("keep an eye on" /
"monitor"), how soon ("as soon as" / "the moment") — plus an optional lead-in about why the user
is away and an optional closing reminder. Names, quoted phrases, numbers and thresholds stay as
written, so the condition the scenario's `eval_sql` checks is still the one the prompt states.
"""

from __future__ import annotations

import random
import re

# (pattern, the alternatives it may become); the pattern's own wording is one of them.
SYNONYMS: tuple[tuple[str, tuple[str, ...]], ...] = (
    (r"\b[Tt]ell me\b", ("tell me", "let me know", "ping me", "notify me")),
    (r"\b[Ll]et me know\b", ("let me know", "tell me", "give me a shout", "notify me")),
    (r"\b[Kk]eep an eye on\b", ("keep an eye on", "monitor", "keep watching", "watch")),
    (r"\b[Aa]s soon as\b", ("as soon as", "the moment", "right when")),
    (r"\b[Ww]atch for\b", ("watch for", "look out for", "keep an eye out for")),
)

LEAD_INS: tuple[str, ...] = (
    "",
    "",
    "I'll be in meetings for a while. ",
    "I'm focusing on something else for a bit. ",
    "Quick favour. ",
    "I'm stepping away from my desk. ",
    "Can you help me with this? ",
)

CLOSERS: tuple[str, ...] = (
    "",
    "",
    " Don't contact me before it has actually happened.",
    " No need to report anything else.",
    " Thanks!",
)


def _capitalised(text: str) -> str:
    return text[:1].upper() + text[1:]


def rephrase(prompt: str, rng: random.Random) -> str:
    """`prompt` with its request wording varied, a lead-in and a closer drawn from `rng`."""
    text = prompt
    for pattern, alternatives in SYNONYMS:
        choice = rng.choice(alternatives)

        def swap(match: re.Match, choice: str = choice) -> str:
            at_start = match.group(0)[:1].isupper()
            return _capitalised(choice) if at_start else choice

        text = re.sub(pattern, swap, text)
    lead, closer = rng.choice(LEAD_INS), rng.choice(CLOSERS)
    # Every lead-in is a sentence of its own, so the prompt after it keeps its capital.
    return lead + _capitalised(text) + closer

"""The preloaded workspace reads like a real Teams chat list at 09:00 on a Thursday: each chat
dated by its own newest message (this morning, yesterday, earlier this week, a date), not all
stamped "five minutes before start"."""

from __future__ import annotations

import json
import re
from collections import defaultdict
from datetime import UTC, datetime
from pathlib import Path

from django.conf import settings

from apps.kit.probe import probe_run, render_probe, state_at_time
from apps.scenarios.format import load_scenario_file

THURSDAY = datetime(2026, 11, 26, tzinfo=UTC)  # the day of the screenshots in issue #28
ROW = re.compile(
    r'class="row-name">(?:<span class="visually-hidden">Unread: </span>)?([^<]+)</span>'
    r'.*?<time class="row-time">([^<]*)</time>',
    re.S,
)


def catalog_messages() -> list[dict]:
    path = Path(settings.SENTINEL_CATALOG_DIR) / "microchat" / "messages.jsonl"
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def test_every_catalog_message_has_its_own_time_in_order_and_in_working_hours():
    """Regression: a conversation's newest messages had no `minutesAgo`, so a preload dated
    them all 08:55; some history sat at 04:02 or 05:40, odd hours for work chats."""
    by_conversation = defaultdict(list)
    for record in catalog_messages():
        assert "minutesAgo" in record, record["id"]
        minutes = record["minutesAgo"]
        clock = (9 * 60 - minutes) % (24 * 60)  # minutes after midnight, 09:00 being now
        assert 8 * 60 <= clock <= 18 * 60 + 30, (record["id"], divmod(clock, 60))
        by_conversation[record["conversation_id"]].append(minutes)
    for conversation, minutes in by_conversation.items():
        assert minutes == sorted(minutes, reverse=True), conversation  # file order is time order
        assert len(set(minutes)) == len(minutes), conversation


def test_the_preloaded_chat_list_dates_chats_as_teams_does():
    dev = load_scenario_file(Path(settings.SENTINEL_SCENARIO_DIR) / "microchat" / "dev.json")
    chat = state_at_time("microchat", dev.events, 0.0)
    html = render_probe(probe_run("microchat", dev.to_run_spec(), day_zero=THURSDAY), chat, 0, "")
    when = dict(ROW.findall(html))
    assert when["Maya Okonjo"] == "08:58"  # the most active chat, minutes ago
    assert when["Hana Sato"] == "08:30"  # earlier this morning
    assert when["Gabriel Nwosu"] == "Yesterday"
    assert when["Aditya Menon"] == "Tue"  # earlier this week: the weekday
    assert when["Board Game Night"] == "19/11"  # a week or more back: the date
    assert len(set(when.values())) > len(when) // 2

"""The preloaded workspace reads like a real Teams chat list at 09:00 on a Thursday: each chat
dated by its own newest message (this morning, yesterday, earlier this week, a date), not all
stamped "five minutes before start". A run starts on any weekday: the meetings stay on working
days and no message text names a weekday that could contradict the date it is shown on."""

from __future__ import annotations

import json
import re
from collections import defaultdict
from datetime import UTC, date, datetime, timedelta
from pathlib import Path

from django.conf import settings

from apps.kit.probe import probe_run, render_probe, state_at_time
from apps.microchat import screens
from apps.scenarios.format import load_scenario_file

THURSDAY = datetime(2026, 11, 26, tzinfo=UTC)  # the day of the screenshots in issue #28
WEEK = [date(2026, 11, 23) + timedelta(days=n) for n in range(7)]  # Monday to Sunday
# A weekday or a day of the month ("the 28th"), which a relative catalog cannot get right.
NAMED_DAY = re.compile(
    r"\b((mon|tues|wednes|thurs|fri|satur|sun)days?|\d{1,2}(st|nd|rd|th))\b", re.I
)
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


def dev_workspace():
    dev = load_scenario_file(Path(settings.SENTINEL_SCENARIO_DIR) / "microchat" / "dev.json")
    return dev, state_at_time("microchat", dev.events, 0.0)


def test_meetings_fall_on_working_days_whatever_weekday_the_run_starts():
    """Regression (issue #28): schedules counted calendar days, so a Thursday run held the
    Design Review and the Roadmap Sync on Saturday and the Retro on Sunday."""
    _, chat = dev_workspace()
    schedule = {c.name: c.schedule[0] for c in chat.conversations.values() if c.schedule}
    assert len(set(schedule.values())) == 5  # the catalog spreads its meetings over five days
    for start in WEEK:
        found = screens.meetings(chat, start, "/microchat/")
        assert {m.title for m in found} == set(schedule), start
        assert all(m.day.weekday() < 5 for m in found), (start, [(m.title, m.day) for m in found])
        day_of = {m.title: m.day for m in found}
        first = start if start.weekday() < 5 else WEEK[0] + timedelta(days=7)
        assert day_of["Sharing Sprint Planning"] == first  # day 0: today, or Monday after
        # The catalog's order kept, one working day to each of its days.
        by_day = sorted(schedule, key=schedule.get)
        assert [day_of[t] for t in by_day] == sorted(day_of[t] for t in by_day), start
        assert len({m.day for m in found}) == 5, start


def test_a_thursday_runs_design_review_is_on_next_weeks_calendar():
    dev, chat = dev_workspace()
    run = probe_run("microchat", dev.to_run_spec(), day_zero=THURSDAY)
    this_week = render_probe(run, chat, 0, "calendar?view=week")
    next_week = render_probe(run, chat, 0, "calendar?view=week&offset=1")
    assert "Sharing Sprint Planning" in this_week and "Weekly Product Review" in this_week
    assert "Design Review: Share Sheet" in next_week and "Notifications Retro" in next_week
    assert "Design Review: Share Sheet" not in this_week


def test_a_weekend_runs_work_week_is_the_coming_one_with_its_first_meetings():
    """Regression: on a Saturday the work week shown was the one just past, and the meetings the
    catalog puts from the Monday after (day 0) were on no page the calendar opened on."""
    dev, chat = dev_workspace()
    saturday = THURSDAY + timedelta(days=2)
    run = probe_run("microchat", dev.to_run_spec(), day_zero=saturday)
    shown = render_probe(run, chat, 0, "calendar?view=week")
    assert "30 Nov – 4 Dec 2026" in shown and "Sharing Sprint Planning" in shown


def test_no_catalog_message_names_a_weekday_or_a_date():
    """Regression (issue #28): "Weekly Product Review on Thursday" when it is tomorrow, "taco
    Friday" on a Wednesday. Times are relative to the run's start, so texts must be too."""
    named = [(r["id"], r["content"]) for r in catalog_messages() if NAMED_DAY.search(r["content"])]
    assert named == []


def test_the_payment_report_names_no_clock_time_it_could_precede():
    """Regression (issue #28): delivered at about 09:09, it said failures began at 09:20."""
    (report,) = (r for r in catalog_messages() if r["id"] == "urg-gabriel-09")
    assert not re.search(r"\b\d{1,2}:\d{2}\b", report["content"])
    assert "card payments are failing" in report["content"].lower()  # the scenario's eval_sql

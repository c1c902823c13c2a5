"""Preloaded mail carries its own age (finding: every preloaded message read "5 min ago", as the
original stamps them all five minutes before the start)."""

from __future__ import annotations

import re

import pytest
from django.test import Client

from apps.kit.links import environment_root
from apps.scenarios.library import get_scenario
from events import lifecycle
from events.projection import state_at

pytestmark = pytest.mark.django_db


def test_an_inbox_reads_as_today_yesterday_and_earlier_newest_first():
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    mail = state_at(run)
    arrivals = [email.arrived_at for email in mail.emails.values()]
    assert len(set(arrivals)) == len(arrivals)  # each message its own moment
    page = Client().get(f"{environment_root(run)}/?folder=inbox").content.decode()
    stamps = re.findall(r'class="when"[^>]*>([^<]+)<', page)
    assert any("min ago" in s for s in stamps) and any(s.startswith("Yesterday") for s in stamps)
    assert any(re.fullmatch(r"[A-Z][a-z]{2} \d{1,2} [A-Z][a-z]{2}", s) for s in stamps), stamps


def test_mail_that_says_today_arrived_today():
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    for email in state_at(run).emails.values():
        if re.search(r"\b(today|tonight|this morning)\b", f"{email.subject} {email.body}", re.I):
            assert -9 * 3600 < email.arrived_at <= 0, email.subject  # since midnight

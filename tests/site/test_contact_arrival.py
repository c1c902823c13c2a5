"""A contact counts from the moment the agent's request reached the server: a server busy with
other runs must not make an agent look late (or let it look on time when it was early)."""

from __future__ import annotations

import pytest
from django.test import AsyncRequestFactory

from apps.control.agent import run_contact
from apps.kit.pages import ARRIVAL
from events import lifecycle
from events.evaluation import contacts_of

pytestmark = pytest.mark.django_db


def test_the_contact_is_timed_at_arrival(tally_spec):
    run = lifecycle.create_run(tally_spec(), speed_factor=2.0)
    lifecycle.start_clock(run, wall=1_000.0)  # sim t = (wall − 1000) × 2
    request = AsyncRequestFactory().get(f"/r/{run.token}/contact")
    request.scope[ARRIVAL] = 1_012.5  # arrived at sim 25 s; served whenever a thread was free
    assert run_contact(request, token=run.token).status_code == 200
    contacts = contacts_of(run)
    assert contacts.first_at == contacts.get_at == 25.0
    run.refresh_from_db()
    assert run.sim_time == 25.0  # the clock froze at the contact, not when it was served

"""A finished MicroMail run over the test cast: preload, late-report at 120, flagged, contact."""

from __future__ import annotations

import pytest

from events import lifecycle
from events.commands import perform_action
from events.evaluation import evaluate
from tests.micromail.cast import CAST


@pytest.fixture
def finished_run(db):
    run = CAST.start()
    lifecycle.advance(run, 60.0)
    perform_action(run, "flag", {"email_id": "budget-review"})
    lifecycle.advance(run, 125.0)
    perform_action(run, "open_email", {"email_id": "late-report"})
    lifecycle.contact(run, method="POST", message="Omar's report is here")
    assert evaluate(run).success
    return run

"""A closed run leaves nothing behind in the process that closed it: its fold, its scenario and
its scheduler hint go, so a server that has served a thousand runs holds what one that served
ten holds (issue #29)."""

from __future__ import annotations

import pytest

from events import lifecycle, projection, scheduler
from events.models import Run, _spec_cache
from tests.micromail.cast import CAST

pytestmark = pytest.mark.django_db


def test_closing_a_run_forgets_what_the_process_kept_for_it():
    run = CAST.start()
    projection.folded_state(run)
    key = (run.pk, run.token)
    assert projection._cache.get((run.pk, run.catalog_hash)) is not None
    assert _spec_cache.get(key) is not None  # remembered at creation
    assert key in scheduler._next_unfired

    lifecycle.close(run)

    assert projection._cache.get((run.pk, run.catalog_hash)) is None
    assert _spec_cache.get(key) is None
    assert key not in scheduler._next_unfired


def test_a_closed_runs_state_is_still_folded_on_demand():
    run = CAST.start()
    before = projection.folded_state(run)
    lifecycle.close(run)
    again = projection.folded_state(Run.objects.get(pk=run.pk))
    assert again.state == before.state
    assert again.seq > before.seq  # the close itself is logged

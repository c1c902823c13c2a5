"""What the engine tells the rest of the site: a run's log grew, its clock was moved, it closed.

The engine never knows who listens (live pages, in apps.kit.live, push regions to browsers):
listeners subscribe to these Django signals, and each notice is sent only once the write that
caused it commits, so a listener never reads a log position that might still roll back.
"""

from __future__ import annotations

import logging

from django.db import transaction
from django.dispatch import Signal

from events.models import EventKind

log = logging.getLogger(__name__)

# Events a page can show: a scenario event or an agent's action (views and lifecycle never are).
LIVE_KINDS = (EventKind.SCENARIO, EventKind.ACTION)

# Sent with run_id and seq: the log of the run grew to `seq` (scenario or action events).
log_grew_signal = Signal()
# Sent with run_id: the run's clock was moved or started by hand (not by time passing).
clock_moved_signal = Signal()
# Sent with run_id: the run was closed; what a process keeps for it (rendered pages) can go.
run_closed_signal = Signal()


def _send_on_commit(signal: Signal, **details: int) -> None:
    def send() -> None:
        # A notice is a convenience (pages also poll and reload); an append is not: a failing
        # listener is logged, never raised into the writer.
        for receiver, result in signal.send_robust(sender=None, **details):
            if isinstance(result, Exception):
                log.warning("listener %r failed on %s", receiver, details, exc_info=result)

    transaction.on_commit(send)


def log_grew(run_id: int, seq: int) -> None:
    """The run's log grew to `seq`; listeners hear it once the write is committed."""
    _send_on_commit(log_grew_signal, run_id=run_id, seq=seq)


def clock_moved(run_id: int) -> None:
    """The run's clock was moved or started; listeners hear it once the write is committed."""
    _send_on_commit(clock_moved_signal, run_id=run_id)


def run_closed(run_id: int) -> None:
    """The run was closed; listeners hear it once the write is committed."""
    _send_on_commit(run_closed_signal, run_id=run_id)

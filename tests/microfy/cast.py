"""The cast of the MicroFy tests, from our catalog (fixtures/microfy): the first ten tracks
preloaded at t=0 (`FIRST_TEN`); "Slow Harbor" (`track-057`, by Neon Pilgrims, its lyrics mention
a lighthouse) not arrived yet. Scenario events and actions are applied as the core applies them,
without a database."""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microfy.environment import MICROFY
from tests.kit import Cast

FIRST_TEN = [f"track-{n:03d}" for n in range(1, 11)]
SLOW_HARBOR = "track-057"

CAST = Cast(
    MICROFY,
    Path(settings.SENTINEL_CATALOG_DIR),
    preload=("preload_tracks", {"track_ids": FIRST_TEN}),
    acts_at=10.0,
)


def arrive(music, track_id: str, *, at: float):
    """`new_track` at `at` (most tests drop one song into the feed)."""
    return CAST.arrive(music, "new_track", {"track_id": track_id}, at=at)

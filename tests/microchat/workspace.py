"""The cast of the MicroChat tests: our catalog (fixtures/microchat) and Chris Taylor's chats
with Gabriel Nwosu, built without a database (scenario events and actions applied as the core
applies them, tests.kit.Cast).

`CAST.preloaded()` is Gabriel's read history; `CAST.preloaded(message_ids=[…], call_ids=[…])`
another starting world.
"""

from __future__ import annotations

from django.conf import settings

from apps.microchat.environment import MICROCHAT
from tests.kit import Cast

GABRIEL_HISTORY = ["dm-gabriel-01", "dm-gabriel-02", "dm-gabriel-03"]  # read in the catalog
GABRIEL_FRESH = ["dm-gabriel-06", "dm-gabriel-07"]  # unread in the catalog
PAYMENTS_DOWN = "urg-gabriel-09"  # urgent, unread
NOOR_FILE = "att-noor-07"  # an image attachment

CAST = Cast(
    MICROCHAT,
    settings.SENTINEL_CATALOG_DIR,
    preload=("preload_messages", {"message_ids": GABRIEL_HISTORY}),
)

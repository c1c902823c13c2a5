"""The cast of the MicroLendar tests, from our catalog (fixtures/microlendar/events.jsonl).

Chris Taylor (the self user) opens the calendar on Thursday 18 September 2025. Preloaded: the
day's first four events (`td-01` standup 9:30, `td-02` grooming 10:00, `td-03` lunch with Rosa,
`td-04` interview), the overlapping pair `cf-01` / `cf-02` on Monday 22 September, the
"Metrics readout" `desc-analytics-1` (Friday 19th) and three tasks (`tk-03` already done).
`td-05` (coffee with Hana, 11:00 today) is added at t=60.

`CAST.act` happens at t=1 unless told.
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microlendar.environment import MICROLENDAR
from tests.kit import Cast

TODAY = "2025-09-18"
PRELOADED = ["td-01", "td-02", "td-03", "td-04", "cf-01", "cf-02", "desc-analytics-1"]
TASKS = ["tk-01", "tk-02", "tk-03"]
LATE_EVENT, LATE_AT = "td-05", 60.0
PRELOAD = {"today": TODAY, "initial_date": TODAY, "event_ids": PRELOADED, "task_ids": TASKS}

CAST = Cast(
    MICROLENDAR,
    Path(settings.SENTINEL_CATALOG_DIR),
    preload=("preload_events", PRELOAD),
    scenario={
        "id": "test-microlendar-cast",
        "environment": "microlendar",
        "prompt": "Test cast.",
        "start_page": "HOST_ADDRESS/microlendar",
        "condition_at": LATE_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "taxonomy": {},
        "events": [
            {"time": 0.0, "type": "preload_events", "payload": PRELOAD},
            {"time": LATE_AT, "type": "new_event", "payload": {"event_id": LATE_EVENT}},
        ],
        "eval_sql": "SELECT 1",
    },
    acts_at=1.0,
    arrives_at=LATE_AT,
)
preloaded, act = CAST.preloaded, CAST.act  # what nearly every test starts from and does

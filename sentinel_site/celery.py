"""Celery app for SENTINEL_TICKER=celery.

Run the worker and beat as two processes (`python -m sentinel_site.production` supervises
both): `celery -A sentinel_site worker --pool=threads` and `celery -A sentinel_site beat`.
`worker --beat` still works for a quick try, but a killed worker leaves its beat child behind.
"""

import os

from celery import Celery

os.environ.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")

HEARTBEAT_S = 1.0

app = Celery("sentinel_site")
app.config_from_object("django.conf:settings", namespace="CELERY")
app.conf.update(
    # A broker outage of any length is waited out, at start-up too, instead of the process
    # exiting; supervisord restarts whatever still dies (sentinel_site/production.py).
    broker_connection_retry=True,
    broker_connection_retry_on_startup=True,
    broker_connection_max_retries=None,
    broker_channel_error_retry=True,
    broker_connection_timeout=2.0,
    broker_transport_options={"socket_connect_timeout": 2.0, "retry_on_timeout": True},
    # fire_run is idempotent (each timeline entry fires once whoever fires it), so a task cut
    # off by a lost connection may simply run again.
    worker_cancel_long_running_tasks_on_connection_loss=True,
    # A publish during an outage gives up after ~1 s rather than blocking a page; the next
    # heartbeat schedules what it would have.
    task_publish_retry_policy={
        "max_retries": 3,
        "interval_start": 0.1,
        "interval_step": 0.2,
        "interval_max": 0.5,
    },
)
app.conf.beat_schedule = {
    "sentinel-heartbeat": {
        "task": "events.heartbeat",
        "schedule": HEARTBEAT_S,
        # Heartbeats queued while no worker ran are stale: one current heartbeat does their job.
        "options": {"expires": 2 * HEARTBEAT_S},
    },
    "sentinel-purge-runs": {"task": "events.purge_runs", "schedule": 3600.0},  # acts once a day
}
app.autodiscover_tasks(["events"])

"""Celery app for SENTINEL_TICKER=celery: `celery -A sentinel_site worker --beat`."""

import os

from celery import Celery

os.environ.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")

app = Celery("sentinel_site")
app.config_from_object("django.conf:settings", namespace="CELERY")
app.conf.beat_schedule = {
    "sentinel-heartbeat": {"task": "events.heartbeat", "schedule": 1.0},
}
app.autodiscover_tasks(["events"])

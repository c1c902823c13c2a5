# Importing the Celery app binds @shared_task to it in every process (Celery's pattern). Only the
# Celery ticker sends or runs tasks, so a process on the embedded defaults never loads Celery: it
# was a tenth of every server's and `manage.py`'s start. (`celery -A sentinel_site` finds the
# app in sentinel_site.celery whatever this says.)
import os

if os.environ.get("SENTINEL_TICKER") == "celery":
    from sentinel_site.celery import app as celery_app

    __all__ = ("celery_app",)

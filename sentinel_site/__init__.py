# Importing the Celery app here binds @shared_task to it in every process (Celery's pattern).
from sentinel_site.celery import app as celery_app

__all__ = ("celery_app",)

"""manage.py purge_runs [--older-than-days N]: delete runs older than N days (events.retention)."""

from __future__ import annotations

from datetime import timedelta

from django.core.management.base import BaseCommand, CommandError

from events.retention import purge_runs, retention_days


class Command(BaseCommand):
    help = "Delete runs (with their logs) older than N days; harness result folders are kept."

    def add_arguments(self, parser):
        parser.add_argument(
            "--older-than-days",
            type=float,
            default=None,
            help="default: SENTINEL_RUN_RETENTION_DAYS (30)",
        )

    def handle(self, *args, older_than_days: float | None, **options):
        days = retention_days() if older_than_days is None else older_than_days
        if days <= 0:
            raise CommandError(
                f"--older-than-days must be more than 0, got {days:g} "
                "(SENTINEL_RUN_RETENTION_DAYS=0 means: never purge)"
            )
        deleted = purge_runs(older_than=timedelta(days=days))
        self.stdout.write(f"purge_runs: deleted {deleted} runs older than {days:g} days")

"""`manage.py import_run run.jsonl`: create a new (closed) run from an export; prints its id."""

import sys
from pathlib import Path

from django.core.management.base import BaseCommand, CommandError

from apps.replay.transfer import TransferError, import_lines


class Command(BaseCommand):
    help = "Import a run exported by export_run; prints the new run id."

    def add_arguments(self, parser):
        parser.add_argument("file", help="a .jsonl file written by export_run ('-' for stdin)")
        parser.add_argument(
            "--catalog",
            help="catalog folder to use (default: the exported one, else SENTINEL_CATALOG_DIR)",
        )

    def handle(self, *args, file, catalog=None, **options):
        try:
            lines = (
                sys.stdin.readlines()
                if file == "-"
                else Path(file).read_text(encoding="utf-8").splitlines()
            )
        except (OSError, UnicodeDecodeError) as error:
            raise CommandError(f"{file}: cannot read: {error}") from None
        try:
            run, warnings = import_lines(lines, catalog_dir=catalog)
        except TransferError as error:
            raise CommandError(f"{file}: {error}") from None
        for warning in warnings:
            self.stderr.write(f"warning: {warning}")
        self.stdout.write(str(run.pk))

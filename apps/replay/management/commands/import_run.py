"""`manage.py import_run run.jsonl`: create a new (closed) run from an export; prints its id."""

import contextlib
import sys

from django.core.management.base import BaseCommand, CommandError

from apps.replay.transfer import TransferError, import_lines
from events.catalog import CatalogError


class Command(BaseCommand):
    help = "Import a run exported by export_run; prints the new run id."

    def add_arguments(self, parser):
        parser.add_argument("file", help="a .jsonl file written by export_run ('-' for stdin)")
        parser.add_argument(
            "--catalog",
            help="catalog folder to use (default: the exported one, else SENTINEL_CATALOG_DIR)",
        )

    def handle(self, *args, file, catalog=None, **options):
        try:  # read as a stream: a file of any size costs one batch of memory
            with (
                contextlib.nullcontext(sys.stdin) if file == "-" else open(file, encoding="utf-8")
            ) as stream:
                run, warnings = import_lines(stream, catalog_dir=catalog)
        except (OSError, UnicodeDecodeError) as error:
            raise CommandError(f"{file}: cannot read: {error}") from None
        except (TransferError, CatalogError) as error:
            raise CommandError(f"{file}: {error}") from None
        for warning in warnings:
            self.stderr.write(f"warning: {warning}")
        self.stdout.write(str(run.pk))

"""`manage.py export_run RUN > run.jsonl`: the run header, then one JSON line per logged event."""

from django.core.management.base import BaseCommand

from apps.replay.management.commands._runs import get_run
from apps.replay.transfer import export_lines


class Command(BaseCommand):
    help = "Write a run (header + one line per event) as JSON Lines to stdout."

    def add_arguments(self, parser):
        parser.add_argument("run", help="run id or token")

    def handle(self, *args, run, **options):
        for line in export_lines(get_run(run)):
            self.stdout.write(line)

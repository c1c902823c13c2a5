"""Shared by the replay commands: find a run by id or token, with a one-line error."""

from django.core.management.base import CommandError

from events.models import Run


def get_run(ref: str) -> Run:
    run = (
        Run.objects.filter(pk=int(ref)).first()
        if ref.isdigit()
        else Run.objects.filter(token=ref).first()
    )
    if run is None:
        raise CommandError(f"run {ref!r} not found (give a run id or token)")
    return run

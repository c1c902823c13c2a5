"""Where a task's timeline lives: the admin of the server that ran it, under the task's run
(apps.bench.timeline_page serves it). `bench grade` prints these and the HTML report links each
task's row to its own; the site is the config's `server_url`, else `./dev serve`'s address (the
embedded server of `bench run` shares its database)."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from apps.bench.grading import ResultSet

DEFAULT_SITE = "http://127.0.0.1:8000"
TIMELINE_PATH = "/admin/events/run/{run}/task/"  # the admin's URL name events_run_task


def timeline_url(site: str | None, run: int) -> str:
    return (site or DEFAULT_SITE).rstrip("/") + TIMELINE_PATH.format(run=run)


def timelines_section(sets: list[ResultSet], site: str | None) -> str:
    """`bench grade`'s closing lines: each graded task's timeline (none when no task has a run)."""
    lines = [
        f"  {rs.name + ': ' if len(sets) > 1 else ''}{row.label}  {timeline_url(site, row.run)}"
        for rs in sets
        for row in rs.rows
        if row.run is not None
    ]
    return "\nTask timelines (admin):\n" + "\n".join(lines) + "\n" if lines else ""

"""Processes as Linux's /proc shows them: whose child a process is.

(apps/bench/reaper.py reads the same field itself: it runs by its path with the standard
library only.)
"""

from __future__ import annotations

from pathlib import Path


def parent_of(pid: int) -> int:
    """The parent's pid, or 0 when the process is gone."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return 0
    return int(stat.rsplit(")", 1)[1].split()[1])  # the field after the state


def live_pids() -> list[int]:
    return [int(entry.name) for entry in Path("/proc").iterdir() if entry.name.isdigit()]

"""Run a command that exits when its parent dies: `python -m sentinel_site.orphan_guard CMD …`.

Every process of the production shape starts through this. After `kill -9` of supervisord its
children used to run on unsupervised, holding the port, so a new `./dev production` failed to
bind it. Linux's parent-death signal (prctl PR_SET_PDEATHSIG, kept across exec) sends each child
SIGTERM the moment supervisord is gone, however it went.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys

PR_SET_PDEATHSIG = 1


def exit_with_parent() -> None:
    """Ask the kernel for SIGTERM when the parent exits (a no-op where there is no prctl)."""
    parent = os.getppid()
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
    except (OSError, AttributeError):
        return  # not Linux: supervisord's own stop still stops its children
    if os.getppid() != parent:  # the parent died before the request took effect
        sys.exit(0)


def main(argv: list[str]) -> None:
    if not argv:
        print("usage: python -m sentinel_site.orphan_guard COMMAND [ARG …]", file=sys.stderr)
        sys.exit(2)
    exit_with_parent()
    os.execvp(argv[0], argv)  # the same process: fd 0 (the shared socket) and the signal stay


if __name__ == "__main__":
    main(sys.argv[1:])

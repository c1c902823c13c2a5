"""What the harness wrote: `harness-records.jsonl` at the top of a result set, one line per
results.json the harness wrote — its path in the set and the SHA-256 of its bytes.

A results.json is a verdict only when the ledger says the harness wrote it, as it is now:
`bench grade` grades it and `bench run` skips its task as done. Any other (a file the harness
did not write, or one changed since) is ignored, and said so. The agent's files are already
kept apart (runner.AgentWorkspace copies them into its trial's `agent/` folder, never a name of
the harness's); the ledger is the second lock. It lies above every task folder, where a copy
into a trial's folder cannot reach, and holds digests, so a file placed or changed by anyone
else is told apart. (No signature: the agent runs as the same user and is not sandboxed, see
README "What an agent can reach"; an agent that writes into the results tree by its absolute
path is outside what any file the harness keeps there can prove.)

A set without a ledger was written before it existed, or by the original harness: it is read
as before. `bench run` starts the ledger before its first task, adopting the results.json the
set already holds (written before any agent of this run started), so a resumed old set is not
run again.
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from apps.bench.layout import LEDGER, RESULTS, TRIAL_PREFIX


def digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _line(root: Path, path: Path, data: bytes, **more: Any) -> bytes:
    entry = {"path": path.relative_to(root).as_posix(), "sha256": digest(data), **more}
    return (json.dumps(entry) + "\n").encode("utf-8")


def start(root: Path) -> int:
    """Create the set's ledger unless it has one, adopting the results.json already there;
    returns how many were adopted. Safe to call from several threads: one creates it."""
    if (root / LEDGER).exists():
        return 0
    found = sorted(root.glob(f"*/*/{RESULTS}")) + sorted(
        root.glob(f"*/*/{TRIAL_PREFIX}*/{RESULTS}")
    )
    lines = []
    for path in found:
        try:
            lines.append(_line(root, path, path.read_bytes(), adopted=True))
        except OSError:
            continue
    root.mkdir(parents=True, exist_ok=True)
    try:
        fd = os.open(root / LEDGER, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
    except FileExistsError:
        return 0
    try:
        os.write(fd, b"".join(lines))
    finally:
        os.close(fd)
    return len(lines)


def record(root: Path, path: Path, data: bytes) -> None:
    """Note that the harness wrote `data` to `path`, a file inside the set `root` (one appended
    line: tasks running in parallel each add theirs)."""
    fd = os.open(root / LEDGER, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        os.write(fd, _line(root, path, data))
    finally:
        os.close(fd)


def write_result(root: Path, path: Path, result: dict[str, Any]) -> None:
    """A task's results.json, as only the harness writes it: recorded in the ledger, then put
    in place atomically (a crash between the two leaves a record of nothing, never a result
    without its record)."""
    data = (json.dumps(result, indent=2, default=str) + "\n").encode("utf-8")
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_bytes(data)
    record(root, path, data)
    tmp.replace(path)


@dataclass(frozen=True)
class Records:
    """A set's ledger as read once: path in the set → digest of what the harness last wrote."""

    root: Path
    digests: dict[str, str] | None  # None: a set without a ledger (read as before)

    @classmethod
    def of(cls, root: Path) -> Records:
        try:
            text = (root / LEDGER).read_text(encoding="utf-8", errors="replace")
        except FileNotFoundError:
            return cls(root, None)
        except OSError:
            return cls(root, {})  # a ledger that cannot be read vouches for nothing
        digests: dict[str, str] = {}
        for line in text.splitlines():
            try:
                entry = json.loads(line)
            except ValueError:
                continue
            if isinstance(entry, dict):
                path, sha = entry.get("path"), entry.get("sha256")
                if isinstance(path, str) and isinstance(sha, str):
                    digests[path] = sha
        return cls(root, digests)

    def vouches(self, path: Path, data: bytes | None = None) -> bool:
        """Whether `path` (read now, or its bytes `data`) holds what the harness wrote there. In
        a set without a ledger, any file there is."""
        if data is None:
            try:
                data = path.read_bytes()
            except OSError:
                return False
        if self.digests is None:
            return True
        try:
            key = path.relative_to(self.root).as_posix()
        except ValueError:
            return False
        return self.digests.get(key) == digest(data)


def not_written_line(path: Path) -> str:
    """The one line that says a results.json is ignored."""
    return f"ignored {path}: not written by the harness (no match in {LEDGER})"

"""Run a scenario's `eval_sql` safely against a materialised snapshot.

The grading database is built here, in the server, by the caller's `build(conn)` (the
environment's tables, session_meta), then serialised and handed to a worker process
(events/sandbox_worker.py, which holds the policy: read-only, allowed functions, bounded value
length, heap, SQL length and time). A worker is killed when the time limit passes, so a single
long expression, which never yields to SQLite's progress handler, cannot hold a server thread,
a core or the server's memory either. A few workers are kept started (WORKERS), so grading
costs a pipe round trip, not a process start.

Every failure is an `SqlOutcome(ok=False, error=<one line>)`, never an exception.
"""

from __future__ import annotations

import contextlib
import marshal
import os
import queue
import select
import sqlite3
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from events import sandbox_worker

TIME_LIMIT_S = 2.0
WORKERS = 2  # evaluations at once per server process; more wait for a free worker
WAIT_FOR_WORKER_S = 10.0
# The worker's own progress handler answers at the limit; the kill is for what it cannot stop.
KILL_GRACE_S = 0.25
SHOWN_VALUE_CHARS = 200  # how much of a returned value a verdict's detail repeats

_WORKER_SCRIPT = Path(sandbox_worker.__file__).resolve()


@dataclass(frozen=True)
class SqlOutcome:
    ok: bool
    value: Any = None
    error: str = ""


def is_truthy(value: Any) -> bool:
    """SQL truth of the first column: NULL, 0, '' and numeric text equal to 0 are false.

    Upstream used Python truthiness, which made the text '0' true.
    """
    if value is None:
        return False
    if isinstance(value, str):
        text = value.strip()
        try:
            return float(text) != 0
        except ValueError:
            return text != ""
    if isinstance(value, bytes):
        return len(value) > 0
    return bool(value)


def shown(value: Any) -> str:
    """`repr(value)`, cut to SHOWN_VALUE_CHARS: a verdict names the value, it does not carry it."""
    text = repr(value[: SHOWN_VALUE_CHARS + 1] if isinstance(value, str | bytes) else value)
    if len(text) <= SHOWN_VALUE_CHARS:
        return text
    size = f"{len(value)} characters" if isinstance(value, str) else f"{len(value)} bytes"
    return f"{text[:SHOWN_VALUE_CHARS]}… ({size})"


def write_session_meta(conn: sqlite3.Connection, meta: Mapping[str, Any]) -> None:
    conn.execute("CREATE TABLE session_meta (key TEXT PRIMARY KEY, value TEXT)")
    conn.executemany(
        "INSERT OR REPLACE INTO session_meta (key, value) VALUES (?, ?)",
        [(key, str(value)) for key, value in meta.items()],
    )


def serialise(build: Callable[[sqlite3.Connection], None]) -> bytes:
    """The database `build(conn)` makes, serialised as the worker takes it."""
    conn = sqlite3.connect(":memory:", check_same_thread=False)
    try:
        build(conn)
        conn.commit()
        # An empty database has no page to serialise: the worker starts from an empty one.
        has_tables = conn.execute("SELECT 1 FROM sqlite_master LIMIT 1").fetchone()
        return conn.serialize() if has_tables else b""
    finally:
        conn.close()


def run_eval_sql(
    sql: str,
    build: Callable[[sqlite3.Connection], None],
    *,
    time_limit_s: float = TIME_LIMIT_S,
) -> SqlOutcome:
    """Build the snapshot with `build(conn)`, then run `sql` read-only in a worker; never raises."""
    return run_eval_sql_on(sql, lambda: serialise(build), time_limit_s=time_limit_s)


def run_eval_sql_on(
    sql: str,
    database: Callable[[], bytes],
    *,
    time_limit_s: float = TIME_LIMIT_S,
) -> SqlOutcome:
    """Run `sql` read-only in a worker on the serialised database `database()` (one that may
    have been built before); never raises."""
    try:
        serialised = database()
    except Exception as exc:  # a materialisation bug is a graded failure, not a 500
        return SqlOutcome(False, error=f"could not build the evaluation tables: {exc}")
    try:
        ok, answer = _POOL.run(marshal.dumps((serialised, sql, time_limit_s)), time_limit_s)
    except SandboxUnavailable as exc:
        return SqlOutcome(False, error=f"eval_sql not run: {exc}")
    return SqlOutcome(True, value=answer) if ok else SqlOutcome(False, error=answer)


# --- the worker pool ------------------------------------------------------------------------------


class SandboxUnavailable(Exception):
    """No worker could take the job (all busy past WAIT_FOR_WORKER_S, or none would start)."""


class _Worker:
    """One worker process and its pipes; used by one thread at a time."""

    def __init__(self) -> None:
        self.process = subprocess.Popen(
            [sys.executable, "-I", "-S", str(_WORKER_SCRIPT)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            close_fds=True,
        )
        self.broken = False  # set when it failed or overran: it is killed, not reused

    def ask(self, job: bytes, deadline: float) -> tuple[bool, Any] | None:
        """The worker's answer, or None when `deadline` (monotonic) passed first."""
        assert self.process.stdin is not None and self.process.stdout is not None
        self.process.stdin.write(sandbox_worker.frame(job))
        self.process.stdin.flush()
        fd = self.process.stdout.fileno()
        header = self._read(fd, 8, deadline)
        if header is None:
            return None
        body = self._read(fd, int.from_bytes(header, "big"), deadline)
        return None if body is None else marshal.loads(body)

    @staticmethod
    def _read(fd: int, size: int, deadline: float) -> bytes | None:
        chunks, left = [], size
        while left:
            remaining = deadline - time.monotonic()
            if remaining <= 0 or not select.select([fd], [], [], remaining)[0]:
                return None
            chunk = os.read(fd, min(left, 1 << 20))
            if not chunk:
                raise BrokenPipeError("the evaluation worker exited")
            chunks.append(chunk)
            left -= len(chunk)
        return b"".join(chunks)

    def kill(self) -> None:
        with contextlib.suppress(OSError):
            self.process.kill()
        self.process.wait()
        for pipe in (self.process.stdin, self.process.stdout):
            if pipe is None:  # never: both are PIPE
                continue
            with contextlib.suppress(OSError):
                pipe.close()


class _Pool:
    """Up to WORKERS started workers, handed to one evaluation at a time."""

    def __init__(self, size: int) -> None:
        self.size = size
        self.lock = threading.Lock()
        self._reset()

    def _reset(self) -> None:
        self.pid = os.getpid()  # a forked child must not share its parent's pipes
        self.idle: queue.LifoQueue[_Worker] = queue.LifoQueue()
        self.started = 0

    def run(self, job: bytes, time_limit_s: float) -> tuple[bool, Any]:
        for attempt in range(2):  # a worker that died while idle is replaced once
            with self._worker() as worker:
                try:
                    answer = worker.ask(job, time.monotonic() + time_limit_s + KILL_GRACE_S)
                except (BrokenPipeError, OSError, ValueError, EOFError):
                    worker.broken = True
                    if attempt:
                        raise SandboxUnavailable("the evaluation worker failed") from None
                    continue
                if answer is None:  # a single expression outlived the limit: stop it
                    worker.broken = True
                    return False, f"eval_sql error: time limit of {time_limit_s:g} s exceeded"
                return answer
        raise AssertionError("unreachable")

    @contextlib.contextmanager
    def _worker(self) -> Iterator[_Worker]:
        worker = self._take()
        try:
            yield worker
        except BaseException:
            worker.broken = True
            raise
        finally:
            if worker.broken or worker.process.poll() is not None:
                self._discard(worker)
            else:
                self.idle.put(worker)

    def _take(self) -> _Worker:
        with self.lock:
            if self.pid != os.getpid():
                self._reset()
            try:
                return self.idle.get_nowait()
            except queue.Empty:
                pass
            if self.started < self.size:
                self.started += 1
                try:
                    return _Worker()
                except OSError as exc:
                    self.started -= 1
                    raise SandboxUnavailable(f"cannot start an evaluation worker: {exc}") from None
        try:
            return self.idle.get(timeout=WAIT_FOR_WORKER_S)
        except queue.Empty:
            raise SandboxUnavailable(
                f"every evaluation worker stayed busy for {WAIT_FOR_WORKER_S:g} s; retry"
            ) from None

    def _discard(self, worker: _Worker) -> None:
        worker.kill()
        with self.lock:
            if self.pid != os.getpid():
                return
            self.started -= 1
            # Start the replacement now, while nobody waits for it.
            try:
                replacement = _Worker()
            except OSError:
                return  # the next evaluation tries again (and says so if it cannot)
            self.started += 1
        self.idle.put(replacement)


_POOL = _Pool(WORKERS)

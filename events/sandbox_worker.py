"""The evaluation sandbox's worker process: runs one `eval_sql` against one grading database.

Started by events.sandbox as `python -I -S <this file>` — the standard library only, no Django,
no project import — so it starts in milliseconds and shares nothing with the server. It reads
jobs from stdin and writes answers to stdout, one length-prefixed `marshal` frame each:

    job:    (database bytes from sqlite3.Connection.serialize(), sql, time limit in seconds)
    answer: (True, value of the first column of the first row) or (False, "one-line error")

The policy lives here because this is where it is enforced. Every resource a query can use is
bounded: the length of any string, blob or row (SQLite's limits API), the SQL text, the heap,
the process's address space, and time — the progress handler stops a long-running statement,
and the server kills this process when a single long expression (one function call never
yields to the progress handler) outlives the limit. Only reads are authorised, and only the
SQL functions in ALLOWED_FUNCTIONS: the original scenarios' (count, lower, date, coalesce, sum,
like) plus deterministic, bounded ones authors reach for; never randomblob, zeroblob, printf,
fts3_tokenizer or anything that reads the host.
"""

from __future__ import annotations

import marshal
import sqlite3
import struct
import sys
import time
from typing import Any, BinaryIO

# Far above any value the grading tables hold (catalog files are ~100 KB), far below harm.
MAX_VALUE_BYTES = 4 * 1024 * 1024
MAX_SQL_CHARS = 100_000
HEAP_BYTES = 256 * 1024 * 1024  # SQLite's own allocations, on top of the database itself
ADDRESS_SPACE_BYTES = 2 * 1024 * 1024 * 1024  # the whole process: a backstop for the heap limit

_LIMITS = {
    sqlite3.SQLITE_LIMIT_LENGTH: MAX_VALUE_BYTES,
    sqlite3.SQLITE_LIMIT_SQL_LENGTH: MAX_SQL_CHARS,
    sqlite3.SQLITE_LIMIT_ATTACHED: 0,
    sqlite3.SQLITE_LIMIT_LIKE_PATTERN_LENGTH: 1_000,
}

ALLOWED_FUNCTIONS = frozenset(
    {
        # aggregates and windows
        *("count", "sum", "total", "avg", "min", "max", "group_concat", "string_agg"),
        *("row_number", "rank", "dense_rank", "percent_rank", "cume_dist", "ntile"),
        *("lag", "lead", "first_value", "last_value", "nth_value"),
        # text, numbers, NULL handling (LIKE and GLOB are calls of like() and glob())
        *("coalesce", "ifnull", "iif", "nullif", "typeof", "like", "glob", "instr", "length"),
        *("octet_length", "lower", "upper", "trim", "ltrim", "rtrim", "replace", "substr"),
        *("substring", "abs", "round", "sign", "hex", "char", "unicode", "quote"),
        *("likely", "unlikely", "likelihood"),
        *("ceil", "ceiling", "floor", "mod", "pow", "power", "sqrt", "exp", "ln", "log"),
        *("log10", "log2"),
        # dates and JSON
        *("date", "time", "datetime", "julianday", "unixepoch", "strftime", "timediff"),
        *("json", "json_extract", "json_type", "json_valid", "json_array_length", "->", "->>"),
    }
)

# Everything a SELECT needs; every other action (INSERT, UPDATE, DELETE, CREATE, DROP, ALTER,
# ATTACH, DETACH, PRAGMA, TRANSACTION, SAVEPOINT …) is denied.
_READ_ACTIONS = frozenset(
    {sqlite3.SQLITE_SELECT, sqlite3.SQLITE_READ, getattr(sqlite3, "SQLITE_RECURSIVE", 33)}
)

Answer = tuple[bool, Any]


def evaluate(database: bytes, sql: str, time_limit_s: float) -> Answer:
    """Run `sql` read-only against a copy of `database`; (True, value) or (False, error)."""
    if len(sql) > MAX_SQL_CHARS:
        return False, f"eval_sql is longer than {MAX_SQL_CHARS} characters"
    conn = sqlite3.connect(":memory:")
    try:
        if database:
            conn.deserialize(database)
        conn.execute(f"PRAGMA hard_heap_limit={HEAP_BYTES + 2 * len(database)}")
        for limit, value in _LIMITS.items():
            conn.setlimit(limit, value)
        denied: list[str] = []
        conn.set_authorizer(lambda action, arg1, arg2, *_: _authorize(action, arg2, denied))
        deadline = time.monotonic() + time_limit_s
        conn.set_progress_handler(lambda: time.monotonic() > deadline, 1_000)
        try:
            row = conn.execute(sql).fetchone()
        except sqlite3.ProgrammingError as exc:
            return False, f"eval_sql rejected: {exc}"
        except sqlite3.Error as exc:
            return False, _explain(exc, denied, time_limit_s)
        except Exception as exc:  # e.g. a value SQLite holds as text that is not UTF-8
            return False, f"eval_sql error: {exc}"
        return True, None if row is None else row[0]
    finally:
        conn.close()


def _authorize(action: int, name: str | None, denied: list[str]) -> int:
    if action in _READ_ACTIONS:
        return sqlite3.SQLITE_OK
    if action == sqlite3.SQLITE_FUNCTION and (name or "").lower() in ALLOWED_FUNCTIONS:
        return sqlite3.SQLITE_OK
    if action == sqlite3.SQLITE_FUNCTION:
        denied.append(name or "?")
    return sqlite3.SQLITE_DENY


def _explain(exc: sqlite3.Error, denied: list[str], time_limit_s: float) -> str:
    message = str(exc)
    if message == "interrupted":
        message = f"time limit of {time_limit_s:g} s exceeded"
    elif denied:
        message = (
            f"not authorized: function {denied[0]}() is not allowed in eval_sql "
            "(see events/sandbox_worker.py ALLOWED_FUNCTIONS)"
        )
    elif "not authorized" in message:
        message = "not authorized: eval_sql may only read (no writes, ATTACH or PRAGMA)"
    elif "too big" in message:
        message = f"a value is longer than the limit of {MAX_VALUE_BYTES} bytes"
    elif "out of memory" in message:
        message = "the query needs more memory than eval_sql may use"
    return f"eval_sql error: {message}"


# --- frames on a pipe -----------------------------------------------------------------------------

_HEADER = struct.Struct(">Q")


def read_frame(stream: BinaryIO) -> bytes | None:
    header = stream.read(_HEADER.size)
    if len(header) < _HEADER.size:
        return None  # the server went away: so does this worker
    (size,) = _HEADER.unpack(header)
    return stream.read(size)


def frame(data: bytes) -> bytes:
    return _HEADER.pack(len(data)) + data


def main() -> None:
    try:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE_BYTES, ADDRESS_SPACE_BYTES))
    except (ImportError, ValueError, OSError):  # a platform without it: the heap limit remains
        pass
    jobs, answers = sys.stdin.buffer, sys.stdout.buffer
    while (job := read_frame(jobs)) is not None:
        database, sql, time_limit_s = marshal.loads(job)
        try:
            answer = evaluate(database, sql, time_limit_s)
        except MemoryError:
            answer = (False, "eval_sql error: the query needs more memory than eval_sql may use")
        answers.write(frame(marshal.dumps(answer)))
        answers.flush()


if __name__ == "__main__":
    main()

"""The production shape: one command starts a supervised set of processes that heals itself.

    python -m sentinel_site.production [--processes N] [--host H] [--port P]
                                       [--ticker process|celery] [--print-config]
    ./dev production …                          # the same, after the usual .venv set-up

Under supervisord (PyPI `supervisor`): N Daphne processes sharing one listening port and the
ticker in processes of its own — one ticker process (`--ticker process`, the default) or a
Celery worker and a Celery beat (`--ticker celery`) —, each restarted whenever it exits or is
killed. It needs `REDIS_URL` (the channel layer that carries pushes between processes; Celery's
broker too) and takes the database from `DATABASE_URL` as usual (PostgreSQL for real load:
SQLite serialises writers across processes).

Choices, and why:
- supervisord restarts what dies (with back-off), stops whole process groups, has a control
  socket (`supervisorctl`) and has been maintained for two decades; honcho/foreman run a
  Procfile but restart nothing, and systemd is not there in a container or a developer's shell.
- Several Daphne processes share one port through supervisord's `fcgi-program`: supervisord
  binds the socket once and hands it to every child as fd 0 (`daphne --fd 0`, the set-up
  Daphne's own documentation gives). The kernel spreads connections over the processes, the
  socket stays open while a process restarts (connections wait in the backlog), and no proxy
  is needed on one machine. Daphne has no SO_REUSEPORT option, and separate ports would need a
  proxy in front just to share load.
- Every child starts through `sentinel_site.orphan_guard` (the kernel's parent-death signal),
  so none outlives supervisord, and a new start stops what an older start of the same shape
  left (`stop_stale`), found by the shape's mark in each process's environment.
- The ticker runs in its own process, never inside a Daphne process: there it shared an event
  loop and a GIL with page rendering, so entries fired as late as the busiest page (finding
  11). The default ticker process is the embedded ticker's own loop (`events.ticker`) with
  nothing else to do; it needs only the database, so a Redis outage cannot delay a timeline
  (pages just miss pushes meanwhile and poll). No one wakes it when a clock starts, so it
  re-reads the live runs every REFRESH_S instead of every second. Two run, both firing
  (idempotent), so a ticker that dies costs no lateness while supervisord restarts it.
- `--ticker celery` keeps the Celery backend for those who run Celery anyway: beat is its own
  program, not `worker --beat`, so killing the worker cannot leave an orphaned beat (finding
  10); broker retries are configured in `sentinel_site/celery.py`; whatever still dies is
  restarted here.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from sentinel_site.exposure import announcement, control_token_for
from sentinel_site.processes import live_pids

REPO = Path(__file__).resolve().parent.parent
TICKERS = ("process", "celery")
SHAPE_MARK = "SENTINEL_PRODUCTION_SHAPE"  # environment variable naming the shape's run folder
REFRESH_S = 0.2  # the ticker process notices a started clock within this (a query each time)
WORKER_THREADS = 4  # fire_run tasks are short database writes; threads wait on the database
TICKERS_RUNNING = 2  # under `--ticker process`: one keeps firing while the other restarts
START_RETRIES = 1000  # with supervisord's growing back-off: a broker down for an hour is waited out


class ProductionError(RuntimeError):
    """A problem the operator can fix; one line."""


@dataclass(frozen=True)
class Shape:
    """What the supervised set runs: N web processes on host:port, a worker and a beat."""

    processes: int = 2
    host: str = "127.0.0.1"
    port: int = 8000
    run_dir: Path = REPO / "var" / "production"
    ticker: str = "process"
    python: str = sys.executable

    def __post_init__(self) -> None:
        if self.ticker not in TICKERS:
            raise ProductionError(
                f"--ticker {self.ticker!r} is not valid; allowed: {', '.join(TICKERS)}"
            )
        if self.processes < 1:
            raise ProductionError(f"--processes must be ≥ 1, got {self.processes}")
        if not 0 < self.port < 65536:
            raise ProductionError(f"--port must be 1–65535, got {self.port}")

    @property
    def programs(self) -> list[str]:
        """Names supervisorctl reports for this shape."""
        web = [f"web:web-{n}" for n in range(self.processes)]
        tickers = [f"ticker:ticker-{n}" for n in range(TICKERS_RUNNING)]
        return web + (tickers if self.ticker == "process" else ["worker", "beat"])

    @property
    def environment(self) -> dict[str, str]:
        """What the shape sets in every process: Daphnes never run a ticker themselves, and each
        carries its shape's mark, by which a later start finds what this one left."""
        return {
            "SENTINEL_TICKER": "celery" if self.ticker == "celery" else "off",
            SHAPE_MARK: str(self.run_dir.resolve()),
        }

    @property
    def conf_path(self) -> Path:
        return self.run_dir / "supervisord.conf"

    @property
    def log_dir(self) -> Path:
        return self.run_dir / "logs"

    def supervisord_conf(self) -> str:
        """The supervisord configuration of this shape (`--print-config` shows it)."""
        run, logs, py = self.run_dir, self.log_dir, self.python
        guard = f"{py} -m sentinel_site.orphan_guard"  # each child exits when supervisord dies
        common = (
            f"directory={REPO}\n"
            "autorestart=true\n"
            "startsecs=1\n"
            f"startretries={START_RETRIES}\n"
            "stopasgroup=true\n"
            "killasgroup=true\n"
            "stopwaitsecs=10\n"
            "redirect_stderr=true\n"
            "stdout_logfile_maxbytes=10MB\n"
            "stdout_logfile_backups=2\n"
        )
        return (
            "; Generated by sentinel_site/production.py — edit that, not this file.\n"
            "[supervisord]\n"
            "nodaemon=true\n"
            f"logfile={logs}/supervisord.log\n"
            f"pidfile={run}/supervisord.pid\n"
            f"childlogdir={logs}\n"
            "\n[unix_http_server]\n"
            f"file={run}/supervisor.sock\n"
            "chmod=0700\n"
            "\n[rpcinterface:supervisor]\n"
            "supervisor.rpcinterface_factory = supervisor.rpcinterface:make_main_rpcinterface\n"
            "\n[supervisorctl]\n"
            f"serverurl=unix://{run}/supervisor.sock\n"
            # One socket bound by supervisord, inherited as fd 0 by every Daphne process.
            "\n[fcgi-program:web]\n"
            f"socket=tcp://{self.host}:{self.port}\n"
            "socket_backlog=1024\n"
            f"command={guard} {py} -m daphne --fd 0 --access-log /dev/null "
            "sentinel_site.asgi:application\n"
            f"numprocs={self.processes}\n"
            "process_name=web-%(process_num)d\n"
            f"stdout_logfile={logs}/web-%(process_num)d.log\n"
            f"{common}"
            f"{self._ticker_programs(f'{guard} {py}', run, logs, common)}"
        )

    def _ticker_programs(self, py: str, run: Path, logs: Path, common: str) -> str:
        if self.ticker == "process":
            # Two, both firing: firing is idempotent, so while one restarts the other keeps the
            # timelines on time (a single restarted ticker left entries up to ≈10 s late).
            return (
                "\n[program:ticker]\n"
                f"command={py} -m sentinel_site.production ticker\n"
                f"numprocs={TICKERS_RUNNING}\n"
                "process_name=ticker-%(process_num)d\n"
                f"stdout_logfile={logs}/ticker-%(process_num)d.log\n"
                f"{common}"
            )
        return (
            "\n[program:worker]\n"
            # Gossip, mingle and event heartbeats are cluster chatter this ticker never uses;
            # gossip's restart is where a lost broker connection crashed the worker.
            f"command={py} -m celery -A sentinel_site worker --pool=threads "
            f"--concurrency={WORKER_THREADS} --without-gossip --without-mingle "
            "--without-heartbeat --loglevel=INFO -n sentinel-worker@%%h\n"
            f"stdout_logfile={logs}/worker.log\n"
            f"{common}"
            "\n[program:beat]\n"
            f"command={py} -m celery -A sentinel_site beat --loglevel=INFO "
            f"--schedule={run}/celerybeat-schedule --pidfile=\n"
            f"stdout_logfile={logs}/beat.log\n"
            f"{common}"
        )

    def write(self) -> Path:
        self.log_dir.mkdir(parents=True, exist_ok=True)
        self.conf_path.write_text(self.supervisord_conf(), encoding="utf-8")
        return self.conf_path


def supervisord_executable() -> str:
    found = Path(sys.executable).with_name("supervisord")
    if found.exists():
        return str(found)
    which = shutil.which("supervisord")
    if which is None:
        raise ProductionError("supervisord is not installed; pip install 'supervisor>=4.2,<5'")
    return which


# What the shape's own processes run (their command lines), to find those a previous start left.


def _command_line(pid: int) -> list[str]:
    try:
        raw = Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return []
    return [part.decode(errors="replace") for part in raw.split(b"\0") if part]


def _shape_mark(pid: int) -> str | None:
    """The run folder of the shape that started `pid` (None: not a shape's process)."""
    try:
        raw = Path(f"/proc/{pid}/environ").read_bytes()
    except OSError:
        return None
    prefix = f"{SHAPE_MARK}=".encode()
    for entry in raw.split(b"\0"):
        if entry.startswith(prefix):
            return entry[len(prefix) :].decode(errors="replace")
    return None


def _is_ours(pid: int, shape: Shape) -> bool:
    """A process a previous start of this shape left: anything carrying this shape's mark
    (supervisord and every program it started, however orphaned). Matching by the mark, not by
    command line, leaves alone what merely looks alike: a Celery worker or Daphne that a test,
    a benchmark or a developer started from this checkout, and every other shape's set."""
    if pid == os.getpid():
        return False
    return _shape_mark(pid) == str(shape.run_dir.resolve())


def stale_processes(shape: Shape) -> list[int]:
    """This shape's supervisord (from its pidfile) and any of its programs left running."""
    found = []
    pidfile = shape.run_dir / "supervisord.pid"
    if pidfile.is_file():
        with contextlib.suppress(ValueError):
            pid = int(pidfile.read_text().strip())
            if _is_ours(pid, shape):
                found.append(pid)
    found += [pid for pid in live_pids() if pid not in found and _is_ours(pid, shape)]
    return found


def stop_stale(shape: Shape, *, grace_s: float = 15.0) -> list[int]:
    """Stop what a previous start of this shape left holding its pidfile and port (its own
    processes only: nothing else on the machine is touched); the pids stopped."""
    stale = stale_processes(shape)
    for pid in stale:
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGTERM)
    deadline = time.monotonic() + grace_s
    while time.monotonic() < deadline and any(_command_line(pid) for pid in stale):
        time.sleep(0.1)
    for pid in stale:
        if _command_line(pid):
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
    return stale


def shape_environment(shape: Shape, base: dict[str, str] | None = None) -> dict[str, str]:
    """The environment every supervised process inherits (`base`: os.environ); Redis required."""
    env = {**(os.environ if base is None else base), **shape.environment}
    if not env.get("REDIS_URL"):
        raise ProductionError(
            "REDIS_URL is required: the processes share pushes (and Celery's broker) through Redis"
        )
    env.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")
    return env


@dataclass
class ProductionSite:
    """A running supervised set: its URL, configuration and supervisord process."""

    base_url: str
    shape: Shape
    supervisord: subprocess.Popen
    env: dict[str, str] = field(repr=False)

    def ctl(self, *args: str) -> str:
        """Run supervisorctl against this set; its output (it exits non-zero when a process
        is not RUNNING, which callers read from the output)."""
        supervisorctl = str(Path(supervisord_executable()).with_name("supervisorctl"))
        return subprocess.run(
            [supervisorctl, "-c", str(self.shape.conf_path), *args],
            capture_output=True,
            text=True,
            timeout=30,
            env=self.env,
        ).stdout

    def states(self) -> dict[str, tuple[str, int | None]]:
        """`{"web:web-0": ("RUNNING", pid), "worker": ("RUNNING", pid), …}`."""
        states = {}
        for line in self.ctl("status").splitlines():
            parts = line.split()
            if len(parts) < 2:
                continue
            pid = None
            if "pid" in parts:
                pid = int(parts[parts.index("pid") + 1].rstrip(","))
            states[parts[0]] = (parts[1], pid)
        return states

    def pids(self) -> list[int]:
        """Every supervised process, and supervisord itself."""
        return [self.supervisord.pid] + [pid for _, pid in self.states().values() if pid]

    def wait_until_running(self, timeout_s: float = 60.0) -> dict[str, tuple[str, int | None]]:
        deadline = time.monotonic() + timeout_s
        while True:
            states = self.states()
            running = [name for name, (state, _) in states.items() if state == "RUNNING"]
            if sorted(running) == sorted(self.shape.programs):
                return states
            if self.supervisord.poll() is not None or time.monotonic() > deadline:
                raise ProductionError(
                    f"the production shape did not start ({states}); see {self.shape.log_dir}"
                )
            time.sleep(0.2)


@contextlib.contextmanager
def production_site(
    processes: int = 2,
    *,
    ticker: str = "process",
    database_url: str | None = None,
    redis_url: str | None = None,
    startup_s: float = 60.0,
) -> Iterator[ProductionSite]:
    """Start the production shape on a free port beside this process (benchmarks, tests),
    on this process's database and library; yield it once every process runs; stop it."""
    from django.conf import settings

    from sentinel_site.site_server import (
        child_environment,
        free_port,
        stop_process_group,
        wait_until_serving,
    )

    run_dir = Path(tempfile.mkdtemp(prefix="sentinel-prod-"))  # short: a unix socket lives here
    shape = Shape(processes=processes, port=free_port(), run_dir=run_dir, ticker=ticker)
    env = shape_environment(
        shape,
        child_environment(database_url, {"REDIS_URL": redis_url or settings.REDIS_URL or ""}),
    )
    conf = shape.write()
    supervisord = subprocess.Popen(
        [supervisord_executable(), "-n", "-c", str(conf)],
        cwd=REPO,
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    site = ProductionSite(f"http://{shape.host}:{shape.port}", shape, supervisord, env)
    try:
        wait_until_serving(supervisord, site.base_url, shape.log_dir, startup_s)
        site.wait_until_running(startup_s)
        yield site
    finally:
        stop_process_group(supervisord)  # supervisord stops its children first, then itself
        shutil.rmtree(run_dir, ignore_errors=True)


def run_ticker() -> None:
    """The ticker process: the embedded ticker's loop, alone in its process, until killed."""
    import asyncio

    import django

    django.setup()
    from events.ticker import InProcessTicker

    async def forever() -> None:
        InProcessTicker(refresh_s=REFRESH_S).ensure_started()
        await asyncio.Event().wait()

    asyncio.run(forever())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m sentinel_site.production",
        description="Start the self-healing production shape under supervisord.",
    )
    parser.add_argument(
        "command",
        nargs="?",
        default="serve",
        choices=("serve", "ticker"),
        help="serve: the supervised set (default); ticker: the ticker process it runs",
    )
    parser.add_argument("--processes", type=int, default=os.cpu_count() or 2, help="Daphnes")
    parser.add_argument("--host", default=os.environ.get("HOST", "127.0.0.1"))
    parser.add_argument("--port", type=int, default=int(os.environ.get("PORT", "8000")))
    parser.add_argument("--ticker", default="process", help=f"one of {', '.join(TICKERS)}")
    parser.add_argument("--print-config", action="store_true", help="print it and exit")
    args = parser.parse_args(argv)
    if args.command == "ticker":
        run_ticker()
        return 0
    try:
        shape = Shape(processes=args.processes, host=args.host, port=args.port, ticker=args.ticker)
        if args.print_config:
            sys.stdout.write(shape.supervisord_conf())
            return 0
        env = shape_environment(shape)
        token = control_token_for(shape.host, env)
        if token:  # beyond loopback, never without one
            env["SENTINEL_CONTROL_TOKEN"] = token
            print(announcement(shape.host, token), flush=True)
        os.environ.update(env)
        import django
        from django.core.management import call_command

        django.setup()
        call_command("migrate", interactive=False, verbosity=0)
        stopped = stop_stale(shape)
        if stopped:
            print(f"production: stopped {len(stopped)} processes a previous start left", flush=True)
        conf = shape.write()
    except ProductionError as exc:
        print(f"production: {exc}", file=sys.stderr)
        return 2
    ticker = "a ticker process" if shape.ticker == "process" else "Celery worker and beat"
    print(
        f"Sentinel Environments (production shape) on http://{shape.host}:{shape.port}/ — "
        f"{shape.processes} Daphne processes and {ticker} under supervisord; "
        f"logs in {shape.log_dir}; status: supervisorctl -c {conf} status",
        flush=True,
    )
    os.execve(supervisord_executable(), ["supervisord", "-n", "-c", str(conf)], env)
    return 0  # not reached


if __name__ == "__main__":
    sys.exit(main())

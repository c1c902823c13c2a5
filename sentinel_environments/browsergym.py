"""Every scenario as a BrowserGym task (`pip install '.[browsergym]'`).

    import gymnasium as gym
    import sentinel_environments.browsergym  # registers browsergym/sentinel.<scenario-id>

    env = gym.make("browsergym/sentinel.micromail-sender-absolute-passive")
    obs, info = env.reset()          # a run is created and its task page opened: the clock starts
    obs, reward, done, _, info = env.step("noop(5000)")           # wait five seconds
    obs, reward, done, _, info = env.step('send_msg_to_user("Kevin Lee wrote.")')  # the report

A task's setup creates a run on a server — `SENTINEL_URL` (with `SENTINEL_CONTROL_TOKEN` if it
has one), else an embedded one this process starts once (`sentinel serve` on a free port, a
fresh temporary data folder, a control token of its own) — from the scenario's document, and
opens its task URL in BrowserGym's browser. The goal is the scenario's prompt. The agent's first
`send_msg_to_user(text)` is its contact, `text` the contact message; the episode then ends with
the server's verdict as the reward (1.0 or 0.0) and `success`, `reaction_time`, the run and the
verdict in `info["task_info"]`. Without a report the episode ends, graded the same way, once the
run's clock reaches the run's end (`kill_at`, at most 600 s): a no-op passes by staying to there.

`noop(wait_ms)` waits. On a fast-forward run (the default clock here) it skips the run's clock
`wait_ms` ahead in simulated time (× the speed factor) instead of sleeping, and returns once the
page shows the new moment; on a live run it sleeps, as BrowserGym's noop does. The browser is
Debian's Chromium (`SENTINEL_CHROMIUM`, else `chromium` on the PATH), never Playwright's
download: BrowserGym's browser launches are given its path.

`task_metadata()` lists the tasks with the paper's categories; `sentinel_environments.agentlab`
makes them an AgentLab benchmark.
"""

from __future__ import annotations

import atexit
import contextlib
import json
import os
import secrets
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import playwright.sync_api
from browsergym.core import _get_global_playwright, _set_global_playwright
from browsergym.core.registration import register_task
from browsergym.core.task import AbstractBrowserTask

from sentinel_environments.client import Client, Clock, Run, SentinelError, Verdict

TASK_PREFIX = "sentinel."
# A condition never comes later than this (authored seconds): a run's end is its kill_at, at
# most this (events.timing.MAX_CONDITION_AT; the harness's `run_end`).
MAX_CONDITION_AT = 600.0
# How long the task's own page work may take (ms): opening its first page, and a page catching
# up with a skip. Not an agent's step: BrowserGym's 5-second ceiling for those would make a
# loaded server's slowness the episode's error.
OURS_TIMEOUT_MS = 60_000
# What Debian's Chromium needs in a container, beside BrowserGym's own launch options.
CHROMIUM_FLAGS = (
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
)
# The live region every page of a run carries: its data-seq is the log position it shows.
SHOWS_SEQ = (
    "seq => { const live = document.querySelector('#sentinel-live');"
    " return !live || Number(live.dataset.seq || 0) >= seq; }"
)


# --- the scenarios --------------------------------------------------------------------------


def scenario_folder() -> Path:
    """The built-in scenarios: `SENTINEL_SCENARIO_DIR`, else the checkout's or the package's."""
    chosen = os.environ.get("SENTINEL_SCENARIO_DIR", "").strip()
    if chosen:
        return Path(chosen)
    from sentinel_site.locations import RESOURCES_DIR  # paths only: no Django

    return RESOURCES_DIR / "scenarios"


def read_scenarios(folder: Path | str | None = None) -> list[tuple[Path, dict[str, Any]]]:
    """(file, document) of every scenario of a folder (`<environment>/<name>.json`), sorted by
    path; a file repeating an earlier id is left out, as the server's library runs the first.
    Not validated here: the server validates a document when a run is created from it."""
    root = Path(folder) if folder is not None else scenario_folder()
    if not root.is_dir():
        raise FileNotFoundError(f"scenario folder not found: {root}")
    found, seen = [], set()
    for path in sorted(root.glob("*/*.json")):
        if path.name == "dev.json":  # an environment's hand-browsing world, not a task
            continue
        try:
            document = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise ValueError(f"{path}: not a JSON scenario: {exc}") from None
        if not isinstance(document, dict) or not isinstance(document.get("id"), str):
            raise ValueError(f"{path}: a scenario needs an 'id'")
        if document["id"] not in seen:
            seen.add(document["id"])
            found.append((path, document))
    return found


def category(document: dict[str, Any]) -> str:
    """The paper's category: `noop` (no condition), else the monitoring approach."""
    if document.get("condition_at") is None:
        return "noop"
    return (document.get("taxonomy") or {}).get("monitoring_approach", "")


def run_end(document: dict[str, Any]) -> float:
    """Authored seconds: the last moment a condition may come, where the episode ends."""
    return min(MAX_CONDITION_AT, float(document.get("kill_at") or MAX_CONDITION_AT))


def task_metadata(folder: Path | str | None = None) -> list[dict[str, Any]]:
    """One row per task: its BrowserGym name, scenario, environment, category and taxonomy."""
    return [
        {
            "task_name": TASK_PREFIX + document["id"],
            "scenario_id": document["id"],
            "environment": document.get("environment", ""),
            "category": category(document),
            **{k: v for k, v in (document.get("taxonomy") or {}).items() if isinstance(v, str)},
        }
        for _, document in read_scenarios(folder)
    ]


def register_scenarios(
    folder: Path | str | None = None,
    *,
    server_url: str | None = None,
    clock: Clock = "fast_forward",
    speed_factor: float = 1.0,
) -> list[str]:
    """Register every scenario of `folder` (default: the built-in ones) as the BrowserGym task
    `sentinel.<scenario-id>` (gym id `browsergym/sentinel.<scenario-id>`), played on `clock` at
    `speed_factor` on the server at `server_url` (default: `SENTINEL_URL`, else an embedded
    one). Registering again replaces the earlier registration. Answers the task names."""
    names = []
    for path, document in read_scenarios(folder):
        name = TASK_PREFIX + document["id"]
        kwargs = {
            "scenario_file": str(path),
            "server_url": server_url,
            "clock": clock,
            "speed_factor": speed_factor,
        }
        with _quiet_reregistration():
            register_task(name, SentinelTask, task_kwargs=kwargs)
        names.append(name)
    return names


@contextlib.contextmanager
def _quiet_reregistration():
    import warnings

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*Overriding environment.*")
        yield


# --- the server -----------------------------------------------------------------------------

_embedded: dict[str, Any] = {}


def embedded_server(startup_s: float = 120.0) -> tuple[str, str]:
    """(base URL, control token) of this process's own server, started on first use: `sentinel
    serve` on a free loopback port with a fresh temporary data folder, stopped at exit."""
    from sentinel_site.site_server import free_port, wait_until_serving  # no Django set up

    if _embedded.get("process") is not None and _embedded["process"].poll() is None:
        return _embedded["url"], _embedded["token"]
    data = Path(tempfile.mkdtemp(prefix="sentinel-browsergym-"))
    port, token = free_port(), secrets.token_urlsafe(24)
    env = dict(os.environ, SENTINEL_CONTROL_TOKEN=token, SENTINEL_FLAT_ENDPOINTS="0")
    command = [sys.executable, "-P", "-m", "sentinel_environments.cli", "--data", str(data)]
    log_path = data / "server.log"
    with open(log_path, "wb") as log:
        process = subprocess.Popen(
            [*command, "serve", "--port", str(port)],
            env=env,
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    atexit.register(_stop, process, data)
    url = f"http://127.0.0.1:{port}"
    wait_until_serving(process, url, log_path, startup_s)
    _embedded.update(process=process, url=url, token=token)
    return url, token


def _stop(process: subprocess.Popen, data: Path) -> None:
    from sentinel_site.site_server import stop_process_group

    stop_process_group(process)
    shutil.rmtree(data, ignore_errors=True)


def _server(server_url: str | None) -> Client:
    url = server_url or os.environ.get("SENTINEL_URL", "").strip()
    if url:
        return Client(url)  # its token, if any, from SENTINEL_CONTROL_TOKEN
    url, token = embedded_server()
    return Client(url, token=token)


# --- the browser ----------------------------------------------------------------------------


def chromium_path() -> str | None:
    chosen = os.environ.get("SENTINEL_CHROMIUM", "").strip()
    return chosen or shutil.which("chromium") or shutil.which("chromium-browser")


class _DebianChromiumType:
    """Playwright's `chromium`, launching Debian's executable with the flags it needs."""

    def __init__(self, chromium: Any, executable: str):
        self._chromium, self._executable = chromium, executable

    def __getattr__(self, name: str) -> Any:
        return getattr(self._chromium, name)

    def launch(self, **kwargs: Any) -> playwright.sync_api.Browser:
        kwargs.setdefault("executable_path", self._executable)
        args = list(kwargs.get("args") or [])
        kwargs["args"] = args + [flag for flag in CHROMIUM_FLAGS if flag not in args]
        return self._chromium.launch(**kwargs)


class _DebianPlaywright:
    def __init__(self, pw: playwright.sync_api.Playwright, executable: str):
        self._pw = pw
        self.chromium = _DebianChromiumType(pw.chromium, executable)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._pw, name)


def use_debian_chromium() -> None:
    """Make BrowserGym's shared Playwright launch Debian's Chromium (the task's page and the
    chat's alike); nothing changes when no `chromium` is installed."""
    executable = chromium_path()
    current = _get_global_playwright()
    if executable and not isinstance(current, _DebianPlaywright):
        _set_global_playwright(_DebianPlaywright(current, executable))


# --- the task -------------------------------------------------------------------------------


class SentinelTask(AbstractBrowserTask):
    """One scenario played as a BrowserGym task (see the module's documentation)."""

    @classmethod
    def get_task_id(cls) -> str:
        return "sentinel"

    def __init__(
        self,
        seed: int,
        scenario_file: str,
        server_url: str | None = None,
        clock: Clock = "fast_forward",
        speed_factor: float = 1.0,
    ) -> None:
        super().__init__(seed)
        self.document = json.loads(Path(scenario_file).read_text(encoding="utf-8"))
        self.server_url, self.clock, self.speed_factor = server_url, clock, speed_factor
        # Playwright's pause after every operation: BrowserGym's default of 1 s is wall time the
        # agent would lose on every step against a clock that does not stop.
        self.slow_mo = 0
        self.client: Client | None = None
        self.run: Run | None = None
        self.outcome: tuple[float, bool, str, dict] | None = None
        use_debian_chromium()  # before BrowserGym launches its browsers (after this __init__)

    def setup(self, page: playwright.sync_api.Page) -> tuple[str, dict]:
        self.client = _server(self.server_url)
        self.run = self.client.create_run(
            self.document, clock=self.clock, speed_factor=self.speed_factor
        )
        if self.clock == "fast_forward":
            self._skip_on_wait(page)
            page.context.on("page", self._skip_on_wait)
        page.goto(self.run.task_url, timeout=OURS_TIMEOUT_MS)  # the clock starts
        info = {
            "run": self.run.id,
            "scenario_id": self.run.scenario_id,
            "environment": self.run.environment,
            "category": category(self.document),
            "clock": self.clock,
            "speed_factor": self.speed_factor,
            "task_url": self.run.task_url,
            "prompt": self.run.prompt,
        }
        return self.run.prompt, info

    def _skip_on_wait(self, page: playwright.sync_api.Page) -> None:
        """`noop(wait_ms)` runs `page.wait_for_timeout(wait_ms)`: on this page it skips the
        run's clock instead, then waits until the page shows the moment it skipped to."""
        run = self.run
        assert run is not None

        def wait_for_timeout(timeout: float) -> None:
            waited = run.wait(seconds=max(0.0, float(timeout)) / 1000 * run.speed_factor)
            if not page.is_closed():
                seq = waited.raw.get("seq", 0)
                page.wait_for_function(SHOWS_SEQ, arg=seq, timeout=OURS_TIMEOUT_MS)

        page.wait_for_timeout = wait_for_timeout  # type: ignore[method-assign,assignment]

    def validate(
        self, page: playwright.sync_api.Page, chat_messages: list[dict]
    ) -> tuple[float, bool, str, dict]:
        if self.outcome is not None:
            return self.outcome
        run = self.run
        assert run is not None
        report = agent_report(chat_messages)
        if report is not None:
            run.contact(report)
        elif run.refresh().status != "completed" and (run.sim_time or 0.0) < run_end(self.document):
            return 0.0, False, "", {}
        self.outcome = graded(run.evaluate())
        return self.outcome

    def teardown(self) -> None:
        if self.run is not None:
            with contextlib.suppress(SentinelError):
                self.run.close()
        if self.client is not None:
            self.client.close()


def agent_report(chat_messages: list[dict]) -> str | None:
    """The agent's first message to the user: an assistant message after the goal (the chat
    opens with BrowserGym's own greeting, then the goal as the user's message)."""
    asked = False
    for message in chat_messages:
        if message.get("role") == "user":
            asked = True
        elif asked and message.get("role") == "assistant":
            return str(message.get("message", ""))
    return None


def graded(verdict: Verdict) -> tuple[float, bool, str, dict]:
    """BrowserGym's (reward, done, message, info) for a verdict: the episode is over."""
    info = {
        "success": verdict.success,
        "reaction_time": verdict.reaction_time,
        "run": verdict.run,
        "verdict": verdict.raw,
    }
    return (1.0 if verdict.success else 0.0), True, "", info


# Importing the module registers the built-in scenarios, as BrowserGym's task packages do.
if os.environ.get("SENTINEL_BROWSERGYM_REGISTER", "1") != "0":
    register_scenarios()

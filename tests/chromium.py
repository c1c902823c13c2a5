"""One Chromium and one Playwright driver per test process, lent to each browser test.

Launching Chromium costs about 0.6 CPU-s and starting Playwright's driver (a Node process) about
0.4, and the suite's browser tests paid both each. Now a test connects the process's Playwright
to the process's Chromium over the DevTools protocol (`connect_over_cdp`) and works in browser
contexts of its own, which `Browser.close()` on a connected browser discards, so no cookie,
storage or page leaks from one test to the next.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import subprocess
import tempfile
import threading
from collections.abc import Iterator
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from playwright.sync_api import Playwright

# The switches Playwright's own `chromium.launch(headless=True)` adds (its chromiumSwitches.ts),
# which change what a page does: no throttling of background tabs and timers (a test with two
# pages), no first-run or default-browser prompts, sRGB colours and no scrollbars in
# screenshots, no back/forward cache (a reload is a reload), and the pointer of a desktop.
PLAYWRIGHT_SWITCHES = [
    "--disable-field-trial-config",
    "--disable-background-timer-throttling",
    "--disable-backgrounding-occluded-windows",
    "--disable-renderer-backgrounding",
    "--disable-back-forward-cache",
    "--disable-breakpad",
    "--disable-component-extensions-with-background-pages",
    "--no-default-browser-check",
    "--disable-default-apps",
    "--disable-dev-shm-usage",
    "--disable-extensions",
    "--disable-features=AvoidUnnecessaryBeforeUnloadCheckSync,DestroyProfileOnBrowserClose,"
    "HttpsUpgrades,HttpsFirstBalancedModeAutoEnable,MediaRouter,PaintHolding,"
    "ThirdPartyStoragePartitioning,OptimizationHints,NetworkTimeServiceQuerying",
    "--allow-pre-commit-input",
    "--disable-hang-monitor",
    "--disable-ipc-flooding-protection",
    "--disable-popup-blocking",
    "--disable-prompt-on-repost",
    "--force-color-profile=srgb",
    "--metrics-recording-only",
    "--no-first-run",
    "--password-store=basic",
    "--use-mock-keychain",
    "--no-service-autorun",
    "--hide-scrollbars",
    "--mute-audio",
    "--blink-settings=primaryHoverType=2,availableHoverTypes=2,"
    "primaryPointerType=4,availablePointerTypes=4",
]
LISTENING = "DevTools listening on "
START_TIMEOUT_S = 60.0  # a fully loaded 2-core machine starts Chromium in seconds, not minutes


class SharedChromium:
    """Chromium started on first use and again if it has died; `endpoint` is its DevTools URL."""

    def __init__(self, executable: str) -> None:
        self.executable = executable
        self._process: subprocess.Popen[str] | None = None
        self._profile: tempfile.TemporaryDirectory[str] | None = None
        self._endpoint = ""

    @property
    def endpoint(self) -> str:
        if self._process is None or self._process.poll() is not None:
            self._start()
        return self._endpoint

    def _start(self) -> None:
        from apps.browser_agent.browser import CHROMIUM_ARGS  # imports Playwright: only when used

        self.stop()
        # A profile left behind is a temporary folder, never a failed test.
        self._profile = tempfile.TemporaryDirectory(
            prefix="sentinel-chromium-", ignore_cleanup_errors=True
        )
        self._process = subprocess.Popen(
            [
                self.executable,
                *CHROMIUM_ARGS,
                *PLAYWRIGHT_SWITCHES,
                f"--user-data-dir={self._profile.name}",
                "--remote-debugging-port=0",  # the port it chose is in the line awaited below
                "--remote-debugging-address=127.0.0.1",
                "--no-startup-window",
            ],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,  # its helpers in one group, stopped with it
        )
        self._endpoint = _await_endpoint(self._process)

    def stop(self) -> None:
        if self._process is not None:
            # The whole group: Chromium's helper processes still write to the profile after the
            # browser process itself has gone.
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self._process.pid, signal.SIGTERM)
            try:
                self._process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(self._process.pid, signal.SIGKILL)
                self._process.wait()
            self._process = None
        if self._profile is not None:
            self._profile.cleanup()
            self._profile = None


def _await_endpoint(process: subprocess.Popen[str]) -> str:
    """The `ws://…` URL Chromium prints once it listens. Its stderr is then drained for good
    (a full pipe would stall Chromium), and a Chromium that exits first is an error that says
    what it printed."""
    assert process.stderr is not None
    found = threading.Event()
    seen: list[str] = []

    def read() -> None:
        for line in process.stderr:  # type: ignore[union-attr]
            if not found.is_set():
                seen.append(line)
                if line.startswith(LISTENING):
                    found.set()
        found.set()  # Chromium exited: wake the waiter, which finds no endpoint

    threading.Thread(target=read, name="chromium-stderr", daemon=True).start()
    if not found.wait(START_TIMEOUT_S) or not seen or not seen[-1].startswith(LISTENING):
        process.kill()
        raise RuntimeError(
            f"Chromium did not start within {START_TIMEOUT_S:.0f} s: {''.join(seen)[-2000:]}"
        )
    return seen[-1][len(LISTENING) :].strip()


class KeptPlaywright:
    """Playwright's driver, started on first use and lent to one test at a time.

    Playwright's sync API runs its event loop in a greenlet of this thread and, after each of
    its calls, marks that loop as the thread's running one (`wait_for_future`), so that the
    next call resumes it. While so marked, Django refuses the thread's database calls (they
    would block a running loop). A browser test does its database work before it takes the
    browser, as before; between lends the mark is cleared, so the tests that follow use the
    database as usual, and it is set again for the next lend — as Playwright itself does when
    a signal interrupted its loop (`greenlet_main`).
    """

    def __init__(self) -> None:
        self._manager = None
        self._playwright: Playwright | None = None
        self._loop: asyncio.AbstractEventLoop | None = None

    def _alive(self) -> bool:
        fiber = getattr(self._manager, "_dispatcher_fiber", None)
        return self._playwright is not None and fiber is not None and not fiber.dead

    @contextlib.contextmanager
    def lent(self) -> Iterator[Playwright]:
        if self._alive():
            asyncio._set_running_loop(self._loop)
        else:  # first use, or the driver went away: a new one
            self.stop()
            from playwright.sync_api import sync_playwright

            self._manager = sync_playwright()
            self._playwright = self._manager.start()
            self._loop = asyncio._get_running_loop()
        try:
            yield self._playwright
        finally:
            asyncio._set_running_loop(None)

    def stop(self) -> None:
        if self._playwright is None:
            return
        if self._alive():
            asyncio._set_running_loop(self._loop)
        with contextlib.suppress(Exception):  # a driver that died has nothing left to stop
            self._playwright.stop()
        asyncio._set_running_loop(None)
        self._manager = self._playwright = self._loop = None

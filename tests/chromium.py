"""One Chromium per test process, reached over the DevTools protocol by each browser test.

Launching Chromium costs about 0.6 CPU-s, and the suite's browser tests launched one each. A test
still starts its own Playwright (whose sync API must not outlive the test: it leaves an event
loop marked running in the thread, which Django's database calls then refuse), but connects it
to this process's Chromium instead of launching one. Each test works in browser contexts of its
own, which `Browser.close()` on a connected browser discards, so no cookie, storage or page
leaks from one test to the next.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import tempfile
import threading

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

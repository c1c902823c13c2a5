"""HTTP client for the control API, with timeouts and retries.

Any failure here is the harness's (or the server's) fault, never the agent's: it raises
`HarnessError`, which the runner reports in error.txt as a harness error.
"""

from __future__ import annotations

import time
from typing import Any

import httpx

RETRIES = 3
BACKOFF_S = 1.0


class HarnessError(RuntimeError):
    """The server or the network failed us; the task's outcome is unknown, not a failure."""


class ControlClient:
    def __init__(self, base_url: str, *, token: str = "", timeout: float = 30.0):
        self.base_url = base_url.rstrip("/")
        self.token = token
        headers = {"Authorization": f"Bearer {token}"} if token else {}
        self._http = httpx.Client(base_url=self.base_url, headers=headers, timeout=timeout)

    def close(self) -> None:
        self._http.close()

    def request(self, method: str, path: str, *, retries: int = RETRIES, **kwargs) -> Any:
        last = ""
        for attempt in range(retries):
            try:
                response = self._http.request(method, path, **kwargs)
            except httpx.HTTPError as exc:
                last = f"{method} {path}: {type(exc).__name__}: {exc}"
            else:
                if response.status_code < 400:
                    return response.json() if response.content else None
                last = f"{method} {path}: HTTP {response.status_code}: {response.text[:2000]}"
                if response.status_code < 500:
                    raise HarnessError(last)  # a 4xx will not get better by retrying
            if attempt + 1 < retries:
                time.sleep(BACKOFF_S * (attempt + 1))
        raise HarnessError(f"{last} (after {retries} attempts)")

    # --- the calls the harness makes -------------------------------------------------------

    def scenarios(self) -> list[dict[str, Any]]:
        return self.request("GET", "/api/scenarios/")

    def scenario(self, scenario_id: str) -> dict[str, Any]:
        return self.request("GET", f"/api/scenarios/{scenario_id}/")

    def create_run(
        self, scenario: str | dict[str, Any], speed_factor: float, clock_mode: str = "live"
    ) -> dict[str, Any]:
        """A run of the library's scenario named `scenario`, or of a whole scenario given."""
        key = "scenario_json" if isinstance(scenario, dict) else "scenario"
        body = {key: scenario, "speed_factor": speed_factor, "clock_mode": clock_mode}
        return self.request("POST", "/api/runs/", json=body)

    def run(self, run_id: int, *, retries: int = RETRIES) -> dict[str, Any]:
        return self.request("GET", f"/api/runs/{run_id}/", retries=retries)

    def evaluate(self, run_id: int) -> dict[str, Any]:
        return self.request("POST", f"/api/runs/{run_id}/evaluate/")

    def events(self, run_id: int) -> list[dict[str, Any]]:
        return self.request("GET", f"/api/runs/{run_id}/events/")

    def export(self, run_id: int) -> list[dict[str, Any]]:
        """The run as `export_run` writes it: a header (run, scenario, verdict), then its events."""
        return self.request("GET", f"/api/runs/{run_id}/export/")

    def close_run(self, run_id: int) -> None:
        self.request("POST", f"/api/runs/{run_id}/close/")

"""The control API of a live test server (the `live_site` fixture), over real HTTP."""

from __future__ import annotations

import json
import urllib.request
from concurrent.futures import ThreadPoolExecutor


def post(base_url: str, path: str, body: dict | None = None) -> dict:
    return call(base_url, "POST", path, body or {})


def call(base_url: str, method: str, path: str, body: dict | None = None):
    request = urllib.request.Request(
        base_url + path,
        data=None if body is None else json.dumps(body).encode(),
        headers={"Content-Type": "application/json"},
        method=method,
    )
    with urllib.request.urlopen(request, timeout=30) as response:
        return json.load(response)


def position(run_id: int, at: float) -> None:
    """Move a live run, before its start, to simulated time `at` (the API's /advance refuses a
    live clock): through the engine, on a thread of its own, since a browser test's thread runs
    Playwright's event loop, where Django refuses ORM calls."""

    def advance() -> None:
        from django.db import connection

        from events import lifecycle
        from events.models import Run

        try:
            lifecycle.advance(Run.objects.get(pk=run_id), at)
        finally:
            connection.close()

    with ThreadPoolExecutor(max_workers=1) as pool:
        pool.submit(advance).result()

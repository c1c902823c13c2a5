"""The control API of a live test server (the `live_site` fixture), over real HTTP."""

from __future__ import annotations

import json
import urllib.request


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

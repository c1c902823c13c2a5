"""Fixtures for the reference agent: a scripted model server and a small static site to act on
(test_tools.py opens it in the agent's browser).

The static site is a real HTTP server with a shop page (a button that writes a line, a search
field, a colour select, a link to a second page) and a contact form shaped like the real one
(`templates/control/contact.html`), whose POSTs it keeps.
"""

from __future__ import annotations

import json
import sys
import threading
import urllib.parse
import urllib.request
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

import pytest

from apps.browser_agent.scripted_model import parse_script, scripted_model_server

REPO = Path(__file__).resolve().parents[2]
AGENT = [sys.executable, "-m", "apps.browser_agent"]

SHOP = """<!DOCTYPE html><html><head><title>Shop</title></head><body>
<h1>Shop</h1>
<a href="/other">Other page</a>
<button onclick="document.getElementById('out').textContent = 'Pressed!'">Press me</button>
<label for="q">Search</label><input id="q" name="q">
<select name="colour" aria-label="Colour"><option>Red</option><option>Blue</option></select>
<details><summary>More</summary><button>Gift wrap</button></details>
<button style="visibility: hidden">Secret</button>
<p id="out">Nothing yet</p>
</body></html>"""
OTHER = "<!DOCTYPE html><html><head><title>Other</title></head><body><h1>Other</h1></body></html>"
CONTACT = """<!DOCTYPE html><html><head><title>Contact</title></head><body><main>
<form method="post" action="/contact"><label for="message">Message</label>
<textarea name="message" id="message"></textarea><button type="submit">Submit</button></form>
</main></body></html>"""
THANKS = "<!DOCTYPE html><html><head><title>Thank you</title></head><body>Thank you.</body></html>"


def served(base_url: str) -> dict[str, int]:
    """The scripted model server's own count of what it served (`GET /v1/_stats`)."""
    with urllib.request.urlopen(base_url + "/_stats", timeout=10) as response:
        return json.load(response)


@dataclass
class StaticSite:
    url: str
    messages: list[str] = field(default_factory=list)  # what the contact form received

    @property
    def contact_url(self) -> str:
        return self.url + "/contact"


def _handler(site: StaticSite) -> type[BaseHTTPRequestHandler]:
    pages = {"/": SHOP, "/other": OTHER, "/contact": CONTACT}

    class Handler(BaseHTTPRequestHandler):
        def log_message(self, format: str, *args: Any) -> None:
            pass

        def do_GET(self) -> None:
            page = pages.get(self.path)
            self._send(200 if page else 404, page or "not found")

        def do_POST(self) -> None:
            body = self.rfile.read(int(self.headers.get("Content-Length") or 0)).decode()
            message = urllib.parse.parse_qs(body).get("message", [""])[0]
            if not message.strip():
                self._send(400, "message must not be empty")
                return
            site.messages.append(message)
            self._send(200, THANKS)

        def _send(self, status: int, html: str) -> None:
            data = html.encode()
            self.send_response(status)
            self.send_header("Content-Type", "text/html; charset=utf-8")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

    return Handler


@contextmanager
def serving_static_site() -> Iterator[StaticSite]:
    site = StaticSite("")
    server = ThreadingHTTPServer(("127.0.0.1", 0), _handler(site))
    server.daemon_threads = True
    site.url = f"http://127.0.0.1:{server.server_address[1]}"
    thread = threading.Thread(
        target=server.serve_forever, kwargs={"poll_interval": 0.05}, daemon=True
    )
    thread.start()
    try:
        yield site
    finally:
        server.shutdown()
        server.server_close()
        thread.join(timeout=5)


@pytest.fixture
def static_site() -> Iterator[StaticSite]:
    with serving_static_site() as site:
        yield site


@pytest.fixture
def scripted_model() -> Iterator:
    """`scripted_model({...script...})` → a running server (`.base_url`, `.model.stats()`)."""
    with ExitStack() as stack:

        def start(script: dict[str, Any]):
            return stack.enter_context(scripted_model_server(parse_script(script)))

        yield start

"""What one client can hold of the server is limited at the socket, against a real Daphne:
- a request body over the limit is refused before it is read (finding: a 300 MB POST to an
  unknown run's actions was received whole, ≈280 MB of memory, before anything refused it);
- slow headers are cut off (finding: one header line every 40 s kept a connection forever);
- connections per client address are capped, idle ones closed (finding: a few hundred such
  connections from one address locked others out)."""

from __future__ import annotations

import contextlib
import json
import socket
import time
from urllib.parse import urlsplit

import httpx
import pytest
from websockets.sync.client import connect as ws_connect

from apps.kit.links import environment_root
from apps.scenarios.library import get_scenario
from events import lifecycle
from sentinel_site.site_server import site_server

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.slow]

LIMIT = 65_536
CONNECTIONS = 6
IDLE_S = 4
ANSWER_S = 30  # a ceiling, not a wait: the answer comes as soon as the server refuses


@pytest.fixture(scope="module")
def small_limit_site(django_db_setup, django_db_blocker):
    limits = {
        "SENTINEL_MAX_BODY_BYTES": str(LIMIT),
        "SENTINEL_HEADER_DEADLINE_S": "1",
        "SENTINEL_IDLE_TIMEOUT_S": str(IDLE_S),
        "SENTINEL_MAX_CONNECTIONS_PER_CLIENT": str(CONNECTIONS),
    }
    with django_db_blocker.unblock(), site_server(extra_env=limits) as base_url:
        yield base_url


def raw_request(base_url: str, head: str, body: bytes = b"") -> bytes:
    """Send `head` (and `body`), then read what the server answers until it closes."""
    address = urlsplit(base_url)
    with socket.create_connection((address.hostname, address.port), timeout=ANSWER_S) as sock:
        sock.sendall(head.encode() + body)
        answer = b""
        while chunk := sock.recv(65_536):
            answer += chunk
        return answer


def test_a_declared_length_over_the_limit_is_refused_before_any_body_is_sent(small_limit_site):
    # One gigabyte declared, not one byte sent: a server that waited for the body would never
    # answer (the socket times out and the test fails).
    answer = raw_request(
        small_limit_site,
        "POST /r/no-such-run/micromail/actions/ HTTP/1.1\r\nHost: 127.0.0.1\r\n"
        "Content-Type: application/json\r\nContent-Length: 1000000000\r\n\r\n",
    )
    status, _, rest = answer.partition(b"\r\n")
    assert status == b"HTTP/1.1 413 Content Too Large"
    assert rest.endswith(
        b"request body too large: the limit is 65536 bytes (SENTINEL_MAX_BODY_BYTES)\n"
    )


def test_a_chunked_body_is_cut_off_as_soon_as_it_passes_the_limit(small_limit_site):
    # Twice the limit in chunks and no final chunk: only counting as it arrives can answer.
    chunk = b"x" * 8192
    body = (f"{len(chunk):x}\r\n".encode() + chunk + b"\r\n") * (2 * LIMIT // len(chunk))
    answer = raw_request(
        small_limit_site,
        "POST /api/runs/ HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
        "Transfer-Encoding: chunked\r\n\r\n",
        body,
    )
    assert answer.startswith(b"HTTP/1.1 413 Content Too Large\r\n")


def test_a_body_within_the_limit_reaches_the_application(small_limit_site):
    # Just under the limit: the API reads it and answers about its content, not its size.
    padding = "x" * (LIMIT - 200)
    response = httpx.post(
        f"{small_limit_site}/api/runs/",
        json={"scenario": "no-such-scenario", "note": padding},
        timeout=ANSWER_S,
    )
    assert response.status_code == 404  # the scenario, not the body, is what is wrong
    assert "no-such-scenario" in response.text


def test_the_server_still_answers_after_refusing(small_limit_site):
    raw_request(
        small_limit_site,
        "POST /api/runs/ HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 99999999\r\n\r\n",
    )
    assert httpx.get(f"{small_limit_site}/api/runs/", timeout=ANSWER_S).status_code == 200


def connect(base_url: str) -> socket.socket:
    address = urlsplit(base_url)
    return socket.create_connection((address.hostname, address.port), timeout=ANSWER_S)


def test_headers_that_trickle_in_are_cut_off(small_limit_site):
    with connect(small_limit_site) as sock:
        sock.sendall(b"GET /api/runs/ HTTP/1.1\r\nHost: 127.0.0.1\r\n")  # and no more
        answer = sock.recv(65_536)
    assert answer.startswith(b"HTTP/1.1 408 Request Timeout\r\n")
    assert answer.endswith(b"headers not received within 1 s\n")


def test_an_idle_connection_is_closed(small_limit_site):
    with connect(small_limit_site) as sock:
        assert sock.recv(1) == b""  # the server closed it (the socket's timeout would raise)


def unanswered(sock: socket.socket) -> bool:
    """The server closed the connection without answering (a close or a reset); False when it
    answered 200."""
    try:
        sock.sendall(b"GET /api/runs/ HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        answer = sock.recv(65_536)
    except (ConnectionResetError, BrokenPipeError):
        return True
    assert answer == b"" or answer.startswith(b"HTTP/1.1 200"), answer[:80]
    return answer == b""


def test_connections_from_one_address_are_capped(small_limit_site):
    held = [connect(small_limit_site) for _ in range(CONNECTIONS)]
    try:
        for sock in held:  # each is served: the server knows all of them before the next
            sock.sendall(b"GET /api/runs/ HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            assert sock.recv(65_536).startswith(b"HTTP/1.1 200")
        with connect(small_limit_site) as extra:
            assert unanswered(extra)
    finally:
        for sock in held:
            sock.close()
    # Closed ones make room: poll, as the server hears of the closes a moment later.
    deadline = time.monotonic() + ANSWER_S
    while time.monotonic() < deadline:
        with connect(small_limit_site) as again:
            if not unanswered(again):
                return
        time.sleep(0.05)
    raise AssertionError("no connection was accepted after the held ones closed")


def test_a_websocket_outlives_the_idle_timeout_and_counts_until_it_closes(small_limit_site):
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    live = f"ws://{urlsplit(small_limit_site).netloc}/r/{run.token}/live"
    page = f"{environment_root(run)}/?folder=inbox"
    with contextlib.ExitStack() as held:
        sockets = [
            held.enter_context(ws_connect(live, open_timeout=ANSWER_S)) for _ in range(CONNECTIONS)
        ]
        with connect(small_limit_site) as extra:
            assert unanswered(extra)  # websockets count: the address is at its cap
        # Past the idle timeout (4 s here) the sockets still answer: Daphne pings them, the
        # HTTP channel they came from no longer times them out.
        time.sleep(IDLE_S + 1)
        for sock in sockets:
            sock.send(json.dumps({"url": page, "seq": 0}))
            assert json.loads(sock.recv(timeout=ANSWER_S))["type"] == "regions"
    deadline = time.monotonic() + ANSWER_S
    while time.monotonic() < deadline:  # the closes free the address's connections
        with connect(small_limit_site) as again:
            if not unanswered(again):
                return
        time.sleep(0.05)
    raise AssertionError("closed websockets still count against their address")

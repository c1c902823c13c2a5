"""A request body over the limit is refused at the socket, before it is read (finding: a 300 MB
POST to an unknown run's actions was received whole, ≈280 MB of memory, before anything could
refuse it). Against a real Daphne: only the server's own socket handling is under test."""

from __future__ import annotations

import socket
from urllib.parse import urlsplit

import httpx
import pytest

from sentinel_site.site_server import site_server

pytestmark = [pytest.mark.django_db(transaction=True)]

LIMIT = 65_536
ANSWER_S = 30  # a ceiling, not a wait: the answer comes as soon as the server refuses


@pytest.fixture(scope="module")
def small_limit_site(django_db_blocker):
    limit = {"SENTINEL_MAX_BODY_BYTES": str(LIMIT)}
    with django_db_blocker.unblock(), site_server(extra_env=limit) as base_url:
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

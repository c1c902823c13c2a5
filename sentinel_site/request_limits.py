"""Limits on what one client can hold of the server, enforced at the socket.

Daphne (Twisted underneath) receives a request's whole body before the application sees it,
then queues all of it at once: a 300 MB POST to any URL cost ≈280 MB of memory before Django
could refuse it. Its connections stayed open for twelve hours of silence, and a client sending
one header line every 40 s held one forever, so a few hundred such connections from one address
could use up the server's file descriptors. Here:

- **Body**: a declared `Content-Length` over SENTINEL_MAX_BODY_BYTES is answered 413 when the
  headers arrive (not one byte of the body kept); a chunked body is counted as it arrives and
  answered 413 the moment it passes the limit. The rest is never read.
- **Headers**: a request's headers must all arrive within SENTINEL_HEADER_DEADLINE_S of its
  first line
  (10 s; 408 otherwise, and the connection closed).
- **Idle connections** close after SENTINEL_IDLE_TIMEOUT_S without a byte (75 s, as common
  proxies do; browsers open a new one when needed).
- **Connections per client address**: at most SENTINEL_MAX_CONNECTIONS_PER_CLIENT open at once
  (websockets included); a connection past that is closed at once.

`install()` makes Daphne build its connections and requests from these classes. It runs when
the ASGI application is imported, before Daphne starts listening, so every way of starting a
server here has it (`./dev serve`, the production shape, the test and harness servers).
"""

from __future__ import annotations

import io
import sys
from collections import Counter

from daphne import http_protocol
from django.conf import settings
from twisted.protocols import policies

from apps.control.parsers import body_limit


def answer(status: str, text: str) -> bytes:
    body = f"{text}\n".encode()
    head = (
        f"HTTP/1.1 {status}\r\n"
        "Content-Type: text/plain; charset=utf-8\r\n"
        f"Content-Length: {len(body)}\r\n"
        "Connection: close\r\n\r\n"
    )
    return head.encode() + body


def refusal(limit: int) -> bytes:
    return answer(
        "413 Content Too Large",
        f"request body too large: the limit is {limit} bytes (SENTINEL_MAX_BODY_BYTES)",
    )


class LimitedWebRequest(http_protocol.WebRequest):
    """Daphne's request, refusing a body over `body_limit()` as soon as that is known, and
    headers that take longer than SENTINEL_HEADER_DEADLINE_S. (Twisted's hooks are camelCase.)"""

    _refused = False
    _received = 0

    def __init__(self, *args, **kwargs):
        from twisted.internet import reactor  # Daphne's, installed before any request

        super().__init__(*args, **kwargs)
        # Created with the request line; cancelled when the last header arrives (gotLength).
        self._header_deadline = reactor.callLater(
            settings.SENTINEL_HEADER_DEADLINE_S, self._headers_too_slow
        )

    def gotLength(self, length):
        self._stop_header_deadline()
        if length is not None and length > body_limit():
            self.content = io.BytesIO()  # what Twisted closes when the connection goes
            self._refuse(refusal(body_limit()))
            return
        super().gotLength(length)

    def handleContentChunk(self, data):
        if self._refused:
            return
        self._received += len(data)
        if self._received > body_limit():
            self._refuse(refusal(body_limit()))
            return
        super().handleContentChunk(data)

    def process(self):
        upgrade = (self.requestHeaders.getRawHeaders(b"upgrade") or [b""])[0]
        if upgrade.lower() == b"websocket":
            # The socket becomes the websocket's, which Daphne pings and times out itself; the
            # HTTP channel, no longer read, would otherwise cut it after its idle timeout.
            self.channel.setTimeout(None)
        return super().process()

    def requestReceived(self, command, path, version):
        if self._refused:
            return  # answered already: the application never sees this request
        super().requestReceived(command, path, version)

    def connectionLost(self, reason):
        self._stop_header_deadline()
        super().connectionLost(reason)

    def _headers_too_slow(self) -> None:
        self._header_deadline = None
        self._refuse(
            answer(
                "408 Request Timeout",
                f"headers not received within {settings.SENTINEL_HEADER_DEADLINE_S} s",
            )
        )

    def _stop_header_deadline(self) -> None:
        if self._header_deadline is not None and self._header_deadline.active():
            self._header_deadline.cancel()
        self._header_deadline = None

    def _refuse(self, response: bytes) -> None:
        self._refused = True
        transport = self.channel.transport
        transport.write(response)
        # Closed once the answer is written, and no longer read: what the client still sends
        # is never received (bytes already buffered are dropped by handleContentChunk).
        transport.loseConnection()


class LimitedHTTPFactory(http_protocol.HTTPFactory):
    """Daphne's HTTP factory with an idle timeout instead of Twisted's twelve hours."""

    def buildProtocol(self, addr):
        protocol = super().buildProtocol(addr)
        if protocol is not None:
            protocol.timeOut = settings.SENTINEL_IDLE_TIMEOUT_S
        return protocol


class ConnectionsPerClient(policies.WrappingFactory):
    """At most SENTINEL_MAX_CONNECTIONS_PER_CLIENT open connections per client address.

    A wrapper around the HTTP factory, so a connection is counted until its socket closes even
    after it became a websocket: Daphne hands a wrapped connection's socket to the websocket
    protocol through the wrapper (as it does under TLS), and the close still comes through it."""

    def __init__(self, wrapped):
        super().__init__(wrapped)
        self.open_from: Counter[str] = Counter()
        self.client_of: dict[object, str] = {}

    def buildProtocol(self, addr):
        host = getattr(addr, "host", "")
        if self.open_from[host] >= settings.SENTINEL_MAX_CONNECTIONS_PER_CLIENT:
            return None  # Twisted closes the connection at once
        protocol = super().buildProtocol(addr)
        if protocol is not None:
            self.open_from[host] += 1
            self.client_of[protocol] = host
        return protocol

    def unregisterProtocol(self, protocol):
        super().unregisterProtocol(protocol)
        host = self.client_of.pop(protocol, None)
        if host is not None:
            self.open_from[host] -= 1
            if self.open_from[host] <= 0:
                del self.open_from[host]


def http_factory(server) -> ConnectionsPerClient:
    """What Daphne's server listens with (it calls `HTTPFactory(server)`)."""
    return ConnectionsPerClient(LimitedHTTPFactory(server))


def install() -> None:
    """Make Daphne build its connections and requests from the classes above (idempotent).
    Outside a Daphne process (a test importing the application) there is nothing to limit, and
    importing Daphne's server here would install its Twisted reactor in that process."""
    daphne_server = sys.modules.get("daphne.server")
    if daphne_server is None:
        return
    http_protocol.WebRequest = LimitedWebRequest  # what HTTPFactory.buildProtocol looks up
    daphne_server.HTTPFactory = http_factory  # what Server.run listens with

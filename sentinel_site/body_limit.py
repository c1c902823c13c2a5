"""Request bodies refused at the socket, before they are read.

Daphne (Twisted underneath) receives a request's whole body before the application sees the
request, then queues all of it for the application at once: a 300 MB POST to any URL cost
≈280 MB of memory before Django could refuse it. `LimitedWebRequest` refuses earlier, where
Twisted hands over the body:

- a declared `Content-Length` over the limit is answered 413 when the headers arrive, and not
  one byte of the body is kept;
- a chunked body (no length declared) is counted as it arrives and answered 413 the moment it
  passes the limit.

Either way the answer is one line naming the limit, and the connection is closed (the rest of
the body is never read). `install()` makes Daphne build its requests from this class; it runs
when the ASGI application is imported, so every way of starting a server here has it
(`./dev serve`, the production shape, the test and harness servers).
"""

from __future__ import annotations

import io

from daphne import http_protocol

from apps.control.parsers import body_limit


def refusal(limit: int) -> bytes:
    text = f"request body too large: the limit is {limit} bytes (SENTINEL_MAX_BODY_BYTES)\n"
    body = text.encode()
    head = (
        "HTTP/1.1 413 Content Too Large\r\n"
        "Content-Type: text/plain; charset=utf-8\r\n"
        f"Content-Length: {len(body)}\r\n"
        "Connection: close\r\n\r\n"
    )
    return head.encode() + body


class LimitedWebRequest(http_protocol.WebRequest):  # Twisted names its hooks in camelCase
    """Daphne's request, refusing a body over `body_limit()` as soon as that is known."""

    _refused = False
    _received = 0

    def gotLength(self, length):
        if length is not None and length > body_limit():
            self.content = io.BytesIO()  # what Twisted closes when the connection goes
            self._refuse()
            return
        super().gotLength(length)

    def handleContentChunk(self, data):
        if self._refused:
            return
        self._received += len(data)
        if self._received > body_limit():
            self._refuse()
            return
        super().handleContentChunk(data)

    def _refuse(self) -> None:
        self._refused = True
        transport = self.channel.transport
        transport.write(refusal(body_limit()))
        # Closed once the answer is written, and no longer read: what the client still sends
        # is never received (bytes already buffered are dropped by handleContentChunk).
        transport.loseConnection()

    def requestReceived(self, command, path, version):
        if self._refused:
            return  # answered already: the application never sees this request
        super().requestReceived(command, path, version)


def install() -> None:
    """Make Daphne build every HTTP request from `LimitedWebRequest` (idempotent)."""
    http_protocol.WebRequest = LimitedWebRequest

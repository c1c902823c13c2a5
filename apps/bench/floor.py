"""The machine's floor for one request: Daphne answering a keep-alive client with no application
work behind it (no Django, no database, no thread).

`bench_protocol` times it with the same client, on the same machine, just before it times the
site, so each of its figures can be read against what any request costs here: the machines of
one kind differ two- to four-fold, and this part of every request is the server's and the
client's (the stack's Daphne and the benchmark's httpx), not the site's code.
"""

from __future__ import annotations

OK = b"ok"


async def application(scope, receive, send):
    if scope["type"] != "http":  # Daphne speaks no lifespan; nothing else is served
        return
    await receive()
    await send(
        {
            "type": "http.response.start",
            "status": 200,
            "headers": [(b"content-type", b"text/plain"), (b"content-length", b"2")],
        }
    )
    await send({"type": "http.response.body", "body": OK})

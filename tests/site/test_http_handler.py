"""Django under ASGI as we serve it: one synchronous chain per request, on a few kept threads."""

from __future__ import annotations

import asyncio
import json
import threading
import time

import pytest
from asgiref.testing import ApplicationCommunicator

from sentinel_site.http_handler import Lanes, RequestThreads, SyncChainHandler
from tests.site.urls import active, reset_concurrency

pytestmark = [
    pytest.mark.django_db(transaction=True),
    pytest.mark.urls("tests.site.urls"),
]


def mark_thread(get_response):
    """A synchronous middleware noting the thread it ran on."""

    def middleware(request):
        request.META["middleware_thread"] = threading.current_thread().name
        return get_response(request)

    return middleware


@pytest.fixture
def app(settings):
    settings.MIDDLEWARE = [*settings.MIDDLEWARE, "tests.site.test_http_handler.mark_thread"]
    threads = RequestThreads(SyncChainHandler(), size=2)
    yield threads
    threads.shutdown()  # closes the kept connections: PostgreSQL must be able to drop the test db


async def get(app, path: str) -> tuple[int, dict]:
    scope = {
        "type": "http",
        "method": "GET",
        "path": path,
        "query_string": b"",
        "headers": [(b"host", b"testserver")],
        "http_version": "1.1",
        "scheme": "http",
        "server": ("testserver", 80),
        "client": ("127.0.0.1", 1),
    }
    communicator = ApplicationCommunicator(app, scope)
    await communicator.send_input({"type": "http.request", "body": b""})
    start = await communicator.receive_output(timeout=10)
    body = b""
    while True:
        message = await communicator.receive_output(timeout=10)
        body += message.get("body", b"")
        if not message.get("more_body"):
            break
    await communicator.wait()
    return start["status"], json.loads(body)


def test_a_request_takes_one_hop_to_its_thread_signals_included(app, monkeypatch):
    """request_started, the chain and view, and request_finished (the response's close) all run
    on the request's thread in one hand-off; Django's own handler took three."""
    from concurrent.futures import ThreadPoolExecutor

    from django.core import signals

    hops = []
    submit = ThreadPoolExecutor.submit
    monkeypatch.setattr(
        ThreadPoolExecutor, "submit", lambda self, *a, **k: hops.append(1) or submit(self, *a, **k)
    )
    seen = []

    def started(**kwargs):
        seen.append(("started", threading.current_thread().name))

    def finished(**kwargs):
        seen.append(("finished", threading.current_thread().name))

    signals.request_started.connect(started)
    signals.request_finished.connect(finished)
    try:
        status, body = asyncio.run(get(app, "/where"))
    finally:
        signals.request_started.disconnect(started)
        signals.request_finished.disconnect(finished)
    assert status == 200
    assert seen == [("started", body["view_thread"]), ("finished", body["view_thread"])]
    assert len(hops) == 1


@pytest.mark.filterwarnings("ignore:StreamingHttpResponse must consume synchronous iterators")
def test_a_streaming_response_is_closed_after_it_is_sent_on_its_thread(app):
    from django.core import signals

    finished = []

    def note(**kwargs):
        finished.append(threading.current_thread().name)

    async def streamed():
        scope = {
            "type": "http", "method": "GET", "path": "/streamed", "query_string": b"",
            "headers": [(b"host", b"testserver")], "http_version": "1.1", "scheme": "http",
            "server": ("testserver", 80), "client": ("127.0.0.1", 1),
        }  # fmt: skip
        communicator = ApplicationCommunicator(app, scope)
        await communicator.send_input({"type": "http.request", "body": b""})
        body = b""
        while True:
            message = await communicator.receive_output(timeout=10)
            if message["type"] == "http.response.body":
                body += message.get("body", b"")
                if not message.get("more_body"):
                    break
        await communicator.wait()
        return body.decode()

    signals.request_finished.connect(note)
    try:
        body = asyncio.run(streamed())
    finally:
        signals.request_finished.disconnect(note)
    assert body.splitlines()[0].startswith("request-")
    assert finished and finished[0].startswith("request-")  # closed on a request thread


def test_middleware_and_view_run_on_one_kept_thread_with_a_kept_connection(app, settings):
    settings.DATABASES["default"]["CONN_MAX_AGE"] = None  # as the servers run (config.py)

    async def three_in_a_row():
        return [await get(app, "/where") for _ in range(3)]

    try:
        answers = [body for status, body in asyncio.run(three_in_a_row()) if status == 200]
    finally:
        settings.DATABASES["default"]["CONN_MAX_AGE"] = 0
    assert len(answers) == 3
    for body in answers:
        assert body["view_thread"] == body["middleware_thread"]
        assert body["view_thread"].startswith("request-")  # RequestThreads' default name
    # One request at a time: the first idle thread is lent each time, with its connection.
    assert {body["view_thread"] for body in answers} == {answers[0]["view_thread"]}
    assert {body["connection"] for body in answers} == {answers[0]["connection"]}


def test_requests_beyond_the_thread_count_wait_their_turn_and_all_complete(app):
    reset_concurrency()

    async def five_at_once():
        return await asyncio.gather(*(get(app, "/slow") for _ in range(5)))

    answers = asyncio.run(five_at_once())
    assert [status for status, _ in answers] == [200] * 5
    assert max(body["most_at_once"] for _, body in answers) == 2


def test_a_thread_count_below_one_is_refused():
    with pytest.raises(ValueError, match="at least one thread"):
        RequestThreads(SyncChainHandler(), size=0)


@pytest.fixture
def lanes(settings):
    handler = SyncChainHandler()
    app = Lanes(
        RequestThreads(handler, size=2, name="agent"),
        RequestThreads(handler, size=2, name="control"),
    )
    yield app
    app.shutdown()


async def both_slow_views_running() -> None:
    """Until two slow views run at once (both threads of their lane busy)."""
    deadline = time.monotonic() + 30
    while active() < 2:
        assert time.monotonic() < deadline, "the slow views never ran together"
        await asyncio.sleep(0.001)


def test_agents_pages_do_not_wait_behind_control_requests(lanes):
    reset_concurrency()

    async def busy_control_then_a_page():
        # Two rounds of work for the control lane's two threads: two run, two wait their turn.
        slow = [asyncio.create_task(get(lanes, "/slow")) for _ in range(4)]
        await both_slow_views_running()
        status, body = await get(lanes, "/r/where")
        answered = time.time()
        control_done = max(answer["ended"] for _, answer in await asyncio.gather(*slow))
        return status, body, answered, control_done

    status, body, answered, control_done = asyncio.run(busy_control_then_a_page())
    assert status == 200 and body["view_thread"].startswith("agent-")
    assert answered < control_done  # not queued behind the control lane's waiting requests


def test_a_request_is_stamped_when_it_arrives_not_when_a_thread_is_free(lanes):
    reset_concurrency()

    async def busy_agents_then_arrival():
        slow = [asyncio.create_task(get(lanes, "/r/slow")) for _ in range(2)]
        await both_slow_views_running()  # both agent threads busy
        sent = time.time()
        status, body = await get(lanes, "/r/arrival")
        freed = min(answer["ended"] for _, answer in await asyncio.gather(*slow))
        return sent, status, body, freed

    sent, status, body, freed = asyncio.run(busy_agents_then_arrival())
    assert status == 200
    # Stamped on arrival, while both threads were busy; run once one was free.
    assert sent <= body["arrived"] < freed <= body["ran"]

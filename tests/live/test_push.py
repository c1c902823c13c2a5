"""Live pages over Channels: a page subscribed to its run is pushed re-rendered live regions.

The cast: two runs of the MicroMail test scenario (virtual clocks at 0), *ours* and *theirs*;
Omar's "Quarterly engineering report" arrives at t=120. Sockets talk to the ASGI router in this
process (in-memory channel layer), so events are fired from this process too.
"""

from __future__ import annotations

import asyncio
import json
import re

import pytest
from asgiref.sync import async_to_sync
from channels.db import database_sync_to_async
from channels.layers import get_channel_layer
from channels.testing import WebsocketCommunicator
from django.test import Client

from apps.kit import live
from apps.kit.live import last_live_seq, render_update
from events import lifecycle
from events.models import Event, EventKind
from events.projection import state_at
from tests.live.pushed import regions
from tests.micromail.cast import CAST, LATE_AT

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

REPORT = "Quarterly engineering report"
WAIT_S = 10  # generous: two cores shared with other test runs


@pytest.fixture(autouse=True)
def in_memory_layer(settings):
    # Sockets and senders share this process: the in-memory layer whatever REDIS_URL says.
    settings.CHANNEL_LAYERS = {"default": {"BACKEND": "channels.layers.InMemoryChannelLayer"}}
    from channels.layers import channel_layers

    channel_layers.backends.clear()
    yield
    channel_layers.backends.clear()


def new_run():
    return CAST.start()


def inbox(run, rest: str = "?folder=inbox") -> str:
    return f"/r/{run.token}/micromail/{rest}"


async def subscribe(run, url: str) -> WebsocketCommunicator:
    from sentinel_site.asgi import router

    socket = WebsocketCommunicator(router, f"/r/{run.token}/live")
    connected, _ = await socket.connect(timeout=WAIT_S)
    assert connected
    seq = await database_sync_to_async(last_live_seq)(run.pk)
    await socket.send_json_to({"url": url, "seq": seq})
    return socket


def run_async(coroutine_function):
    return async_to_sync(coroutine_function)()


def test_a_fired_event_is_pushed_to_its_own_run_only():
    ours, theirs = new_run(), new_run()

    async def story():
        our_page = await subscribe(ours, inbox(ours))
        their_page = await subscribe(theirs, inbox(theirs))
        assert await our_page.receive_nothing(timeout=0.3)  # nothing new yet
        await database_sync_to_async(lifecycle.advance)(ours, LATE_AT)
        message = await our_page.receive_json_from(timeout=WAIT_S)
        assert await their_page.receive_nothing(timeout=1)
        await our_page.disconnect()
        await their_page.disconnect()
        return message

    message = run_async(story)
    assert message["type"] == "regions" and message["url"] == inbox(ours)
    pushed = regions(message)
    assert set(pushed) == {"sim-clock", "favorites", "folders", "message-list", "reading-pane"}
    assert REPORT in pushed["message-list"] and 'hx-swap-oob="true"' in pushed["message-list"]
    assert message["seq"] == last_live_seq(ours.pk)


def test_an_action_in_one_tab_updates_another_tab_of_the_same_run():
    run = new_run()
    message = pushed_after_a_flag(run, inbox(run))
    assert 'aria-label="Unflag “Q3 budget review”"' in regions(message)["message-list"]


def test_a_live_render_logs_no_view_and_opens_nothing():
    run = new_run()
    views_before = Event.objects.filter(run=run, kind=EventKind.VIEW).count()

    async def story():
        page = await subscribe(run, inbox(run, "?folder=inbox&email=budget-review"))
        await database_sync_to_async(lifecycle.advance)(run, LATE_AT)
        message = await page.receive_json_from(timeout=WAIT_S)
        await page.disconnect()
        return message

    message = run_async(story)
    assert "Q3 budget review" in regions(message)["reading-pane"]  # the open email stays open
    assert Event.objects.filter(run=run, kind=EventKind.VIEW).count() == views_before
    assert not Event.objects.filter(run=run, kind=EventKind.ACTION).exists()
    assert state_at(run).states["budget-review"].is_read is False


def test_an_event_fired_before_subscribing_is_pushed_on_subscribe():
    run = new_run()
    seq_shown = last_live_seq(run.pk)
    lifecycle.advance(run, LATE_AT)

    async def story():
        from sentinel_site.asgi import router

        page = WebsocketCommunicator(router, f"/r/{run.token}/live")
        assert (await page.connect(timeout=WAIT_S))[0]
        await page.send_json_to({"url": inbox(run), "seq": seq_shown})
        message = await page.receive_json_from(timeout=WAIT_S)
        await page.disconnect()
        return message

    assert REPORT in regions(run_async(story))["message-list"]


def test_a_socket_cannot_watch_another_runs_page():
    ours, theirs = new_run(), new_run()

    async def story():
        page = await subscribe(ours, inbox(theirs))
        message = await page.receive_json_from(timeout=WAIT_S)
        await page.disconnect()
        return message

    assert run_async(story)["type"] == "error"


def test_a_socket_for_an_unknown_run_is_refused():
    async def story():
        from sentinel_site.asgi import router

        page = WebsocketCommunicator(router, "/r/no-such-token/live")
        connected, _ = await page.connect(timeout=WAIT_S)
        await page.disconnect()
        return connected

    assert run_async(story) is False


def test_pushed_forms_leave_the_csrf_token_to_the_browser():
    # One frame serves every subscriber: the client fills in its own page's token.
    run = new_run()

    async def story():
        page = await subscribe(run, inbox(run))
        await database_sync_to_async(lifecycle.advance)(run, LATE_AT)
        message = await page.receive_json_from(timeout=WAIT_S)
        await page.disconnect()
        return message

    html = run_async(story)["html"]
    assert 'name="csrfmiddlewaretoken" value=""' in html
    assert not re.search(r'name="csrfmiddlewaretoken" value="[^"]', html)


def test_polling_answers_204_until_the_log_grows_then_the_regions():
    run = new_run()
    browser = Client()
    seq = last_live_seq(run.pk)
    poll = f"/r/{run.token}/live"
    assert browser.get(poll, {"url": inbox(run), "seq": seq}).status_code == 204
    lifecycle.advance(run, LATE_AT)
    response = browser.get(poll, {"url": inbox(run), "seq": seq})
    assert response.status_code == 200
    body = json.loads(response.content)
    assert REPORT in regions(body)["message-list"] and body["seq"] > seq
    assert browser.get(poll, {"url": inbox(run), "seq": body["seq"]}).status_code == 204


def test_polling_answers_once_the_clock_reaches_the_pages_due():
    run = new_run()  # 09:00; the shell clock next changes at 09:01
    browser = Client()
    seq = last_live_seq(run.pk)
    poll = f"/r/{run.token}/live"
    assert browser.get(poll, {"url": inbox(run), "seq": seq, "due": 60}).status_code == 204
    lifecycle.advance(run, 61.0)  # no event: only the clock moved
    response = browser.get(poll, {"url": inbox(run), "seq": seq, "due": 60})
    assert response.status_code == 200
    body = json.loads(response.content)
    assert body["seq"] == seq and body["next_change"] == 120.0
    assert "09:01" in regions(body)["sim-clock"] and "6 min ago" in regions(body)["message-list"]
    assert browser.get(poll, {"url": inbox(run), "seq": seq, "due": 120}).status_code == 204


def test_polling_refuses_a_due_that_is_not_a_time():
    run = new_run()
    response = Client().get(f"/r/{run.token}/live", {"url": inbox(run), "seq": 0, "due": "soon"})
    assert response.status_code == 400 and "due" in response.content.decode()


def test_one_render_serves_a_log_position_and_a_clock_window(monkeypatch):
    run = new_run()
    url, seq = inbox(run), last_live_seq(run.pk)
    renders = []
    monkeypatch.setattr(
        live, "render_update", lambda *args: renders.append(args) or render_update(*args)
    )

    first = live.shared_render(run, url, seq, 0.0)
    assert live.shared_render(run, url, seq, 59.0) is first  # 09:00 still reads 09:00
    lifecycle.advance(run, 61.0)
    turned = live.shared_render(run, url, seq, 61.0)
    assert turned is not first and turned.next_change == 120.0
    assert live.shared_render(run, url, seq, 100.0) is turned
    assert live.shared_render(run, url, seq + 1, 100.0) is not turned  # the log grew
    assert len(renders) == 3


def test_polling_refuses_another_runs_url():
    ours, theirs = new_run(), new_run()
    response = Client().get(f"/r/{ours.token}/live", {"url": inbox(theirs), "seq": 0})
    assert response.status_code == 400 and "not a page of this run" in response.content.decode()


def test_group_messages_use_the_configured_layer():
    # The broadcast path itself: a plain sync caller reaches a group member.
    run = new_run()

    async def story():
        layer = get_channel_layer()
        channel = await layer.new_channel()
        await layer.group_add(f"run.{run.pk}", channel)
        await database_sync_to_async(lifecycle.advance)(run, LATE_AT)
        return [await asyncio.wait_for(layer.receive(channel), WAIT_S) for _ in range(2)]

    moved, grew = run_async(story)
    assert moved == {
        "type": "run.clock_moved",
        "run": run.pk,
        "clock": {
            "status": "running_manual",
            "started_at": None,
            "sim_time": LATE_AT,
            "skipped": 0.0,
        },
    }
    assert grew["type"] == "run.log_grew" and grew["run"] == run.pk


def delete(run, email_id: str) -> None:
    from events.commands import perform_action

    perform_action(run, "delete", {"email_id": email_id})


def test_a_purged_open_item_stops_pushes_quietly():
    run = new_run()

    async def story():
        page = await subscribe(run, inbox(run, "?folder=junk&email=prize-scam"))
        await database_sync_to_async(delete)(run, "prize-scam")  # to Deleted Items: still shown
        moved = await page.receive_json_from(timeout=WAIT_S)
        await database_sync_to_async(delete)(run, "prize-scam")  # purged: the page is a 404 now
        await database_sync_to_async(lifecycle.advance)(run, LATE_AT)
        nothing = await page.receive_nothing(timeout=1)
        await page.send_json_to({"url": inbox(run), "seq": 0})  # the socket still works
        inbox_update = await page.receive_json_from(timeout=WAIT_S)
        await page.disconnect()
        return moved, nothing, inbox_update

    moved, nothing, inbox_update = run_async(story)
    assert "In Deleted Items" in regions(moved)["reading-pane"]
    assert nothing
    assert REPORT in regions(inbox_update)["message-list"]


def test_a_log_that_grows_without_changing_what_a_page_shows_moves_only_its_position():
    """Nothing moves without a cause: flagging an inbox message changes nothing on Sent Items,
    so that tab gets no regions, only its new log position (a fast-forward agent reads it)."""
    run = new_run()
    sent = inbox(run, "?folder=sent")
    message = pushed_after_a_flag(run, sent, settled_first=True)
    assert message["type"] == "regions" and message["url"] == sent
    assert message["html"] == "" and message["seq"] == last_live_seq(run.pk)


def pushed_after_a_flag(run, url: str, *, settled_first: bool = False) -> dict:
    """What a tab subscribed to `url` is pushed when another tab flags "Q3 budget review"
    (`settled_first`: the subscription pushes nothing before it)."""
    tab_a = Client()

    async def story():
        tab_b = await subscribe(run, url)
        if settled_first:
            assert await tab_b.receive_nothing(timeout=0.5)  # subscribed: the page as it is noted
        response = await database_sync_to_async(tab_a.post)(
            inbox(run, "emails/budget-review/flag"), {"back": "?folder=inbox"}
        )
        assert response.status_code == 302
        message = await tab_b.receive_json_from(timeout=WAIT_S)
        await tab_b.disconnect()
        return message

    return run_async(story)

"""The websocket behind live pages: `/r/<token>/live`, one socket per open page.

Protocol (JSON text frames):
- client → server, on open and after every in-page navigation:
  `{"url": "/r/<token>/micromail/?folder=inbox", "seq": <log position the page shows>}`
- server → client, whenever the run's log grows by a scenario or action event:
  `{"type": "regions", "seq": N, "html": "<nav id=… data-live hx-swap-oob=\"true\">…"}`
  and `{"type": "error", "detail": …}` for a URL that is not one of this run's pages.

The socket joins the channel group of its run only, so one run's events never reach another
run's pages.
"""

from __future__ import annotations

import logging

from channels.db import database_sync_to_async
from channels.generic.websocket import AsyncJsonWebsocketConsumer

from events import live

log = logging.getLogger(__name__)


class RunLiveConsumer(AsyncJsonWebsocketConsumer):
    async def connect(self) -> None:
        token = self.scope["url_route"]["kwargs"]["token"]
        self.run = await database_sync_to_async(live.open_run)(token)
        if self.run is None:
            await self.close(code=4404)
            return
        headers = dict(self.scope.get("headers") or [])
        self.host = headers.get(b"host", b"testserver").decode("latin-1")
        self.url: str | None = None
        self.seen = 0
        self.group = live.group_name(self.run.pk)
        await self.channel_layer.group_add(self.group, self.channel_name)
        await self.accept()

    async def disconnect(self, code) -> None:
        if getattr(self, "group", None):
            await self.channel_layer.group_discard(self.group, self.channel_name)

    async def receive_json(self, content, **kwargs) -> None:
        url = content.get("url") if isinstance(content, dict) else None
        try:
            live.page_path_for(self.run, url)
        except live.NotLive as exc:
            await self.send_json({"type": "error", "detail": str(exc)})
            return
        seq = content.get("seq")
        self.url = url
        self.seen = seq if isinstance(seq, int) and seq >= 0 else 0
        # An event may have fired between the page's render and this subscription.
        latest = await database_sync_to_async(live.last_live_seq)(self.run.pk)
        if latest > self.seen:
            await self.push(latest)

    async def run_log_grew(self, message: dict) -> None:
        if self.url is not None and message["seq"] > self.seen:
            await self.push(message["seq"])

    async def push(self, seq: int) -> None:
        url = self.url
        try:
            update = await live.shared_update(self.run, url, seq, self.host)
        except live.NotLive as exc:
            # e.g. the open item was purged meanwhile: the page stays as it is until navigated.
            log.info("no live update for %s: %s", url, exc)
            self.seen = max(self.seen, seq)
            return
        except Exception:  # a page that fails to render must not close every push after it
            log.exception("live render of %s failed", url)
            self.seen = max(self.seen, seq)
            return
        if url != self.url:
            return  # the page navigated meanwhile; its new URL brought its own push
        self.seen = max(self.seen, update.seq, seq)
        await self.send(text_data=update.text)

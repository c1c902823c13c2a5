"""The cast of the MicroTube tests, from our catalog (fixtures/microtube):

- the self user, Chris Taylor (user000), whose channel is `ch-self`;
- Pixel Forge (`ch-pixel-forge`, subscribed), run by Felix Amadi, with the Skyward Colony 2
  walkthrough `vid-pixel-01` and two comments on it; its desk-setup video `vid-pixel-03` is
  uploaded at 120 s;
- Reel Talk (`ch-reel-talk`, not subscribed) with `vid-reel-01`;
- two notifications: Kitchen Table Code's upload (`notif-01`, unread) and "Your comment received
  25 likes" (`notif-09`, already read); Pixel Forge's live notice (`notif-08`) arrives at 120 s.
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microtube.environment import MICROTUBE
from tests.kit import Cast

ME = "user000"
WALKTHROUGH = "vid-pixel-01"
DESK_SETUP = "vid-pixel-03"
UPLOAD_AT = 120.0
PRELOAD = {
    "video_ids": [WALKTHROUGH, "vid-pixel-02", "vid-reel-01", "vid-self-01"],
    "channel_ids": ["ch-pixel-forge", "ch-reel-talk", "ch-self"],
    "comment_ids": ["cmt-01", "cmt-02"],
    "notification_ids": ["notif-01", "notif-09"],
    "subscribed_channel_ids": ["ch-pixel-forge"],
    "watched_video_ids": ["vid-self-01"],
}

CAST = Cast(
    MICROTUBE,
    Path(settings.SENTINEL_CATALOG_DIR),
    preload=("preload_videos", PRELOAD),
    # A run over the cast: preload at 0, Pixel Forge's upload and live notice at 120 s.
    scenario={
        "id": "microtube-cast-desk-setup",
        "environment": "microtube",
        "start_page": "HOST_ADDRESS/microtube",
        "prompt": "When Pixel Forge uploads, like the new video.",
        "condition_at": UPLOAD_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [
            {"time": 0.0, "type": "preload_videos", "payload": PRELOAD},
            {"time": UPLOAD_AT, "type": "new_video", "payload": {"video_id": DESK_SETUP}},
            {
                "time": UPLOAD_AT,
                "type": "new_notification",
                "payload": {"notification_id": "notif-08"},
            },
        ],
        "eval_sql": f"SELECT EXISTS(SELECT 1 FROM video_states WHERE video_id='{DESK_SETUP}' AND isLiked=1)",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "active"},
    },
    acts_at=200.0,
    arrives_at=UPLOAD_AT,
)

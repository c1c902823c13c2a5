"""The cast of the MicroGram tests, from our catalog (fixtures/microgram):

- the self user, Chris Taylor (ctaylor, user000), and his bouldering post;
- Noor Haddad's market haul (`post-market-haul`, 2 comments), in the feed from the start;
- Marco Bellini's desk post (`post-desk-plant-jungle`, 5 comments), arriving at 120 s;
- two stories, one watched by the time the test looks;
- a tray that changes under an open story viewer (`TRAY_EVENTS`): sgrant's desk view, the
  newest of three, then amenon's climbing night, which expires at 30 s, then rduarte's coffee
  run; hquinn's new story arrives at 60 s;
- Maya's thread (read) and Tobias's (two unread), Rosa's mockup thread arriving at 120 s;
- a read follow (`act-01`) and an unread follow from Marco (`act-10`).
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microgram.environment import MICROGRAM
from tests.kit import Cast

ME = "user000"
MARCO = "user012"
MARKET = "post-market-haul"
DESK = "post-desk-plant-jungle"
OWN_POST = "post-ctaylor-01-bouldering"
STORIES = ["story-rduarte-coffee-run", "story-amenon-climb-night"]
PRELOAD = {
    "post_ids": [OWN_POST, MARKET],
    "story_ids": STORIES,
    "message_ids": ["dm-maya", "dm-tobias"],
    "activity_ids": ["act-01", "act-10"],
}
ARRIVES_AT = 120.0
SGRANT = "story-sgrant-desk-view"  # newer than both STORIES
TRAY = [*STORIES, SGRANT]  # oldest first
LATE_STORY = "story-hquinn-new-feature"
EXPIRES_AT, POSTED_AT = 30.0, 60.0
TRAY_EVENTS = [
    {"time": 0.0, "type": "preload_posts", "payload": {**PRELOAD, "story_ids": TRAY}},
    {"time": EXPIRES_AT, "type": "expire_story", "payload": {"story_id": STORIES[1]}},
    {"time": POSTED_AT, "type": "new_story", "payload": {"story_id": LATE_STORY}},
]

# A run over the cast: preload at 0; Marco's post and Rosa's thread at 120 (the condition).
CAST = Cast(
    MICROGRAM,
    Path(settings.SENTINEL_CATALOG_DIR),
    preload=("preload_posts", PRELOAD),
    scenario={
        "id": "microgram-cast-mockup",
        "environment": "microgram",
        "start_page": "HOST_ADDRESS/microgram",
        "prompt": "Like Marco's desk post when it appears.",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [
            {"time": 0.0, "type": "preload_posts", "payload": PRELOAD},
            {"time": ARRIVES_AT, "type": "new_post", "payload": {"post_id": DESK}},
            {"time": ARRIVES_AT, "type": "new_message", "payload": {"message_id": "dm-rosa"}},
        ],
        "eval_sql": f"SELECT EXISTS(SELECT 1 FROM post_states WHERE post_id='{DESK}' AND isLiked=1)",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "active"},
    },
    acts_at=200.0,
    arrives_at=ARRIVES_AT,
)

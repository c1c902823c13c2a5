"""The cast of the MicroHub tests, from our catalog (fixtures/microhub): the Tandem repository
of MyMicro Inc., seen by the self user Chris Taylor (ctaylor).

- preloaded: issues i1 (steps to reproduce), i3 (board unresponsive), i8 (closed) and i12,
  pull requests pr1 (open, approved) and pr4 (merged), every commit but c26–c28, runs 1–7;
- the star curve of the original's "stars" scenarios: 1,847 at 0, 2,000 at 587.31, 2,080 at 720;
- later: issue i14 (TOTP) at 120, pull request pr5 at 150, commit c26 at 160, run-9 at 170.

`CAST.act` happens at 200 unless told, `CAST.arrive` at 120 (when the TOTP issue is filed).
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microhub.environment import MICROHUB
from tests.kit import Cast

ME = "ctaylor"
STAR_WAYPOINTS = [[0.0, 1847], [587.31, 2000], [720.0, 2080]]
PRELOAD = {
    "issue_ids": ["i1", "i3", "i8", "i12"],
    "pr_ids": ["pr1", "pr4"],
    "commit_ids": [f"c{n}" for n in range(1, 26)],
    "run_ids": [f"run-{n}" for n in range(1, 8)],
    "star_waypoints": STAR_WAYPOINTS,
}
TOTP_ISSUE, TOTP_AT = "i14", 120.0
ARRIVALS = [
    {"time": TOTP_AT, "type": "new_issue", "payload": {"issue_id": TOTP_ISSUE}},
    {"time": 150.0, "type": "new_pull_request", "payload": {"pr_id": "pr5"}},
    {"time": 160.0, "type": "new_commit", "payload": {"commit_id": "c26"}},
    {"time": 170.0, "type": "new_workflow_run", "payload": {"run_id": "run-9"}},
]

CAST = Cast(
    MICROHUB,
    Path(settings.SENTINEL_CATALOG_DIR),
    preload=("preload_repo", PRELOAD),
    # A run over the cast: comment on the TOTP issue once it is filed (at 120).
    scenario={
        "id": "microhub-cast-totp",
        "environment": "microhub",
        "start_page": "HOST_ADDRESS/microhub",
        "prompt": "Comment on the issue about TOTP when it is filed.",
        "condition_at": TOTP_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [{"time": 0.0, "type": "preload_repo", "payload": PRELOAD}, *ARRIVALS],
        "eval_sql": "SELECT EXISTS(SELECT 1 FROM user_created_comments "
        f"WHERE target_type='issue' AND target_id='{TOTP_ISSUE}')",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "active"},
    },
    acts_at=200.0,
    arrives_at=TOTP_AT,
)

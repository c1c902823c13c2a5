"""The cast of the MicroDin tests, from our catalog (fixtures/microdin):

- the self user, Chris Taylor (user000), an APM at MyMicro Inc.;
- Silas Grant's anniversary post `post-01`, and Chris's own `post-self-1`;
- invitations from Kevin Lee (`conn-01`) and Imani Brooks-Hale (`conn-02`);
- the thread with Marco Bellini (`conv-02`, two unread messages, one more arriving later);
- CloudPeak's Infrastructure Engineer posting `job-09` (Kubernetes, in its requirements only);
- Maya Okonjo's like (`notif-01`, unread).
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microdin.environment import MICRODIN
from tests.kit import Cast

ME = "user000"
KUBERNETES_JOB = "job-09"
PRELOAD = {
    "post_ids": ["post-01", "post-self-1"],
    "connection_ids": ["conn-01", "conn-02"],
    "conversation_ids": ["conv-02"],
    "notification_ids": ["notif-01", "notif-11"],
    "job_ids": ["job-01", "job-06"],
}
LATE_JOB_AT = 120.0

# A run over the cast: preload at 0, the Kubernetes job at 120 (the condition).
CAST = Cast(
    MICRODIN,
    Path(settings.SENTINEL_CATALOG_DIR),
    preload=("preload_posts", PRELOAD),
    scenario={
        "id": "microdin-cast-kubernetes",
        "environment": "microdin",
        "start_page": "HOST_ADDRESS/microdin",
        "prompt": "Apply to the Kubernetes role when it is posted.",
        "condition_at": LATE_JOB_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [
            {"time": 0.0, "type": "preload_posts", "payload": PRELOAD},
            {"time": LATE_JOB_AT, "type": "new_job", "payload": {"job_id": KUBERNETES_JOB}},
        ],
        "eval_sql": f"SELECT EXISTS(SELECT 1 FROM job_states WHERE job_id='{KUBERNETES_JOB}' AND isApplied=1)",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "active"},
    },
    acts_at=200.0,
    arrives_at=LATE_JOB_AT,
)

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
from apps.microdin.state import Network
from apps.scenarios.format import parse_scenario
from events.catalog import load_catalog
from events.registry import ActionRejected, LoggedEvent, PayloadError, validate_payload

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


def catalog():
    return load_catalog(Path(settings.SENTINEL_CATALOG_DIR))


def scenario_event(type: str, payload: dict, *, at: float = 0.0, seq: int = 1) -> LoggedEvent:
    return LoggedEvent(seq, at, "scenario", type, payload)


def preloaded(**changes) -> Network:
    """The network right after the cast's preload at t=0."""
    network = MICRODIN.initial_state(catalog())
    return MICRODIN.apply(network, scenario_event("preload_posts", {**PRELOAD, **changes}))


def arrive(network: Network, type: str, payload: dict, at: float = LATE_JOB_AT) -> Network:
    return MICRODIN.apply(network, scenario_event(type, payload, at=at, seq=2))


def act(network: Network, name: str, payload: dict, *, at: float = 200.0) -> Network:
    """Validate, decide and apply one agent action, as the core does (without a database)."""
    action = MICRODIN.actions[name]
    try:
        validate_payload(action.schema, payload, what=f"action {name}")
    except PayloadError as exc:
        raise ActionRejected(str(exc)) from None
    recorded = action.decide(network, dict(payload))
    return MICRODIN.apply(network, LoggedEvent(100, at, "action", name, recorded))


def cast_scenario(**overrides) -> dict:
    """A run over the cast: preload at 0, the Kubernetes job at 120 (the condition)."""
    data = {
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
    }
    data.update(overrides)
    return parse_scenario(data, source="tests/microdin").to_run_spec()

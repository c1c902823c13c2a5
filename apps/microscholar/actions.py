"""What an agent can do in MicroScholar: `Action(schema, decide, reduce, page)` per name.

- `save` / `unsave` — the library. Set, not toggled as in the original: repeating a request, or
  two tabs racing, cannot flip a paper back out of the library by accident.
- `cite` — opening the Cite dialog, which is what the original records (isCited, never unset).
- `mark_alert_read`.

`decide` refuses ids that are not indexed (unknown and not-yet-arrived look the same: 404);
reducers trust the log and never raise.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

from apps.kit.deciding import checking, found, marking
from apps.kit.state import with_items
from apps.kit.streaming import id_payload
from apps.microscholar.state import Paper, Scholar
from events.registry import Action, ActionRejected, LoggedEvent, PageStep

PaperId = id_payload("PaperId", "paper_id", "id of an indexed paper")
AlertId = id_payload("AlertId", "alert_id", "id of an alert that has arrived")


def existing_paper(scholar: Scholar, paper_id: str) -> Paper:
    return found(scholar.papers, paper_id, "paper", "in the index")


decide_on_paper = checking("papers", "paper_id", "paper", "in the index")


def decide_on_alert(scholar: Scholar, payload: dict) -> dict:
    if payload["alert_id"] not in scholar.alerts:
        raise ActionRejected(f"no alert {payload['alert_id']!r}", status=404)
    return payload


def reduce_mark_alert_read(scholar: Scholar, event: LoggedEvent) -> Scholar:
    alert_id = event.payload["alert_id"]
    if alert_id not in scholar.alerts or scholar.alert_read.get(alert_id):
        return scholar
    return with_items(scholar, "alert_read", [(alert_id, True)])


# --- where a person does it (forms marked data-action="<action>" in the templates) -------------


def paper_page(scholar: Scholar, payload: dict) -> PageStep:
    """The paper's own page, whose first Save / Remove form is the paper's."""
    existing_paper(scholar, payload["paper_id"])
    return PageStep(f"papers/{payload['paper_id']}", {"paper_id": payload["paper_id"]})


def cite_page(scholar: Scholar, payload: dict) -> PageStep:
    """Opening the Cite dialog is the action (an implicit action of the `cite` page)."""
    existing_paper(scholar, payload["paper_id"])
    return PageStep(f"papers/{payload['paper_id']}/cite")


def alerts_page(scholar: Scholar, payload: dict) -> PageStep:
    decide_on_alert(scholar, payload)
    return PageStep("alerts", {"alert_id": payload["alert_id"]})


marks_paper = marking(PaperId, decide_on_paper, "paper_states", "paper_id", page=paper_page)

ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "save": marks_paper(saved=True, help="Add a paper to My library."),
        "unsave": marks_paper(saved=False, help="Remove a paper from My library."),
        "cite": marks_paper(
            cited=True,
            page=cite_page,
            help="Open a paper's Cite dialog (formatted citations and export links).",
        ),
        "mark_alert_read": Action(
            AlertId,
            decide_on_alert,
            reduce_mark_alert_read,
            help="Mark an alert read.",
            page=alerts_page,
        ),
    }
)

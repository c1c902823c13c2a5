"""Every text and list an agent can put in an action is bounded (apps/kit/fields.py): a
multi-megabyte mail body or a 100,000-address `to` list was accepted, logged and rendered."""

from __future__ import annotations

from typing import Any

import pytest
from rest_framework.test import APIClient

from apps.kit.fields import LIST_ITEMS, TEXT_CHARS
from apps.scenarios.library import get_scenario
from events import lifecycle
from events.models import Event, EventKind
from events.registry import environment_names, get_environment


def unbounded(schema: dict[str, Any], where: str = "") -> list[str]:
    """The parts of a JSON schema that take a text or a list of any size."""
    found = []
    for option in schema.get("anyOf", [schema]):
        choices = "enum" in option or "const" in option  # a Literal: bounded by its choices
        if option.get("type") == "string" and "maxLength" not in option and not choices:
            found.append(where or "(payload)")
        if option.get("type") == "array":
            if "maxItems" not in option:
                found.append(f"{where}[]")
            found += unbounded(option.get("items", {}), f"{where}[]")
    for name, part in schema.get("properties", {}).items():
        found += unbounded(part, f"{where}.{name}" if where else name)
    return found


@pytest.mark.parametrize("environment", environment_names())
def test_every_action_field_an_agent_writes_is_bounded(environment):
    actions = get_environment(environment).actions
    problems = {
        name: found
        for name, action in actions.items()
        if (found := unbounded(action.schema.model_json_schema()))
    }
    assert problems == {}, "declare these fields with a kind from apps.kit.fields"


@pytest.mark.django_db
@pytest.mark.parametrize(
    "payload,named",
    [
        ({"to": ["a@example.com"], "subject": "hi", "body": "x" * (TEXT_CHARS + 1)}, "body"),
        ({"to": [f"p{n}@example.com" for n in range(LIST_ITEMS + 1)], "subject": "hi"}, "to"),
    ],
    ids=["body", "to"],
)
def test_an_oversized_field_is_refused_naming_it_and_nothing_is_logged(payload, named):
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    before = Event.objects.filter(run=run, kind=EventKind.ACTION).count()
    response = APIClient().post(
        f"/r/{run.token}/actions", {"action": "send", "payload": payload}, format="json"
    )
    assert response.status_code == 400
    detail = response.json()["detail"]
    assert f"'{named}'" in detail and len(detail) < 300  # the value is not sent back whole
    assert Event.objects.filter(run=run, kind=EventKind.ACTION).count() == before

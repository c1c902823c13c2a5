"""Scenarios as database rows, so authors can edit them in the admin.

The files in `scenarios/<env>/*.json` stay the one source of truth; these rows are an editable
mirror kept in step with them (`apps.scenarios.sync`): files are imported when the admin opens,
an admin edit is written through to its file, and `dumpscenarios` / `loadscenarios` copy rows
and files by hand. A dump
must reproduce an unedited file byte for byte, so each row also keeps the *shape* of its file:
the order of its top-level keys, which numbers were written as integers, unknown keys, and each
event's own key order. JSON values are stored as text (`OrderedJSONField`) because PostgreSQL's
jsonb reorders object keys, which would reorder a taxonomy or payload on the way back out.
"""

from __future__ import annotations

import json
from typing import Any

from django import forms
from django.db import models

# The key order our own files use; a scenario created in the admin is written this way.
DEFAULT_KEY_ORDER = (
    "id",
    "environment",
    "start_page",
    "watch_page",
    "prompt",
    "condition_at",
    "event_timeline_end",
    "kill_at",
    "events",
    "annotator_notes",
    "taxonomy",
    "eval_sql",
    "solution",
)
DEV_KEY_ORDER = ("id", "environment", "event_timeline_end", "events")
EVENT_KEY_ORDER = ("time", "type", "payload")


class OrderedJSONFormField(forms.JSONField):
    def prepare_value(self, value):
        if isinstance(value, forms.fields.InvalidJSONInput):
            return value
        return json.dumps(value, ensure_ascii=False)


class OrderedJSONField(models.TextField):
    """Any JSON value, stored as its text: object key order and int/float survive every backend."""

    def from_db_value(self, value, expression, connection):
        return None if value is None else json.loads(value)

    def to_python(self, value):
        if isinstance(value, str):
            try:
                return json.loads(value)
            except json.JSONDecodeError:
                return value
        return value

    def get_prep_value(self, value):
        return None if value is None else json.dumps(value, ensure_ascii=False)

    def value_to_string(self, obj):
        return self.get_prep_value(self.value_from_object(obj))

    def formfield(self, **kwargs):
        return super().formfield(**{"form_class": OrderedJSONFormField, **kwargs})


class Scenario(models.Model):
    """One scenario file, keyed by its path relative to the scenario folder.

    The path, not the id, is the key: two upstream files share an id
    (microfy playlists-relative-passive and public-playlists-relative-passive).
    """

    path = models.CharField(
        max_length=300,
        unique=True,
        help_text="relative to the scenario folder, e.g. micromail/x.json",
    )
    scenario_id = models.CharField("id", max_length=200, db_index=True)
    environment = models.CharField(max_length=64, db_index=True)
    prompt = models.TextField(blank=True)
    start_page = models.CharField(max_length=300, blank=True)
    watch_page = models.CharField(
        max_length=300,
        blank=True,
        help_text="the page the prompt tells the agent to watch, e.g. HOST_ADDRESS/microdin/jobs "
        "(empty: the start page)",
    )
    condition_at = models.FloatField(
        null=True, blank=True, help_text="authored seconds; empty = no-op"
    )
    event_timeline_end = models.FloatField()
    kill_at = models.FloatField(null=True, blank=True)
    eval_sql = models.TextField(blank=True)
    taxonomy = OrderedJSONField(default=dict, blank=True)
    annotator_notes = models.TextField(blank=True)
    solution = OrderedJSONField(default=list, blank=True)
    is_dev = models.BooleanField(default=False, help_text="a dev.json (populate-everything) file")
    # Denormalised from taxonomy for the admin filters.
    monitoring_approach = models.CharField(
        "action requirement", max_length=16, blank=True, db_index=True
    )
    milestone_type = models.CharField("criterion type", max_length=16, blank=True, db_index=True)
    # The file's shape, for byte-identical dumps.
    key_order = OrderedJSONField(default=list, blank=True, help_text="top-level keys in file order")
    int_keys = OrderedJSONField(
        default=list, blank=True, help_text="numbers written without a decimal point"
    )
    extra = OrderedJSONField(
        default=dict, blank=True, help_text="unknown top-level keys, kept verbatim"
    )
    # Only for a file whose text is not json.dump(indent=2) output: its original text, used while
    # the row still renders to `original_canonical_sha256` (i.e. nobody edited it).
    original_text = models.TextField(blank=True)
    original_canonical_sha256 = models.CharField(max_length=64, blank=True)
    # sha256 of the file's text when this row and its file last agreed: tells a file changed on
    # disk from a row edited in the admin (empty: a row from before rows followed their files).
    file_sha256 = models.CharField(max_length=64, blank=True, editable=False)
    updated_at = models.DateTimeField(auto_now=True)

    class Meta:
        ordering = ["environment", "path"]

    def __str__(self) -> str:
        return self.scenario_id

    def save(self, *args, **kwargs):
        taxonomy = self.taxonomy if isinstance(self.taxonomy, dict) else {}
        self.monitoring_approach = str(taxonomy.get("monitoring_approach", ""))[:16]
        self.milestone_type = str(taxonomy.get("milestone_type", ""))[:16]
        super().save(*args, **kwargs)

    @property
    def is_noop(self) -> bool:
        return self.condition_at is None and not self.is_dev


class TimelineEvent(models.Model):
    scenario = models.ForeignKey(Scenario, on_delete=models.CASCADE, related_name="timeline")
    position = models.PositiveIntegerField(default=0)
    time = models.FloatField(help_text="authored seconds")
    type = models.CharField(max_length=64)
    payload = OrderedJSONField(default=dict, blank=True)
    time_is_int = models.BooleanField(default=False, editable=False)
    key_order = OrderedJSONField(default=list, blank=True, editable=False)
    extra = OrderedJSONField(default=dict, blank=True, editable=False)

    class Meta:
        ordering = ["scenario_id", "position", "id"]

    def __str__(self) -> str:
        return f"{self.time:g}s {self.type}"

    def as_json(self) -> dict[str, Any]:
        values: dict[str, Any] = {
            "time": int(self.time)
            if self.time_is_int and self.time == int(self.time)
            else self.time,
            "type": self.type,
            "payload": self.payload,
            **(self.extra or {}),
        }
        order = list(self.key_order or EVENT_KEY_ORDER)
        order += [k for k in values if k not in order]
        return {k: values[k] for k in order if k in values}

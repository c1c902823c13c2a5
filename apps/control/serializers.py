"""Request and response shapes of the control plane."""

from __future__ import annotations

import math

from rest_framework import serializers

from apps.agent_site import links
from apps.scenarios.format import ScenarioError, parse_scenario
from apps.scenarios.library import get_scenario
from events.models import ClockMode, Run
from events.registry import UnknownEnvironment, environment_names, get_environment
from events.timing import SpeedFactorError, validate_speed_factor


def _speed_factor(value: float) -> float:
    try:
        return validate_speed_factor(value)
    except SpeedFactorError as exc:
        raise serializers.ValidationError(str(exc)) from None


class TimelineEntrySerializer(serializers.Serializer):
    time = serializers.FloatField()
    type = serializers.CharField()
    payload = serializers.DictField(required=False, default=dict)

    def validate_time(self, value: float) -> float:
        if not math.isfinite(value) or value < 0:
            raise serializers.ValidationError(f"must be a finite number ≥ 0, got {value}")
        return value


class InitPayloadSerializer(serializers.Serializer):
    """SentinelBench's `/init` body (extra keys such as kill_at, prompt, taxonomy are ignored)."""

    environment = serializers.CharField()
    event_timeline_end = serializers.FloatField()
    eval_sql = serializers.CharField(required=False, allow_blank=True, default="")
    condition_at = serializers.FloatField(required=False, allow_null=True, default=None)
    speed_factor = serializers.FloatField(required=False, default=1.0, validators=[_speed_factor])
    events = TimelineEntrySerializer(many=True)
    start_page = serializers.CharField(
        required=False, allow_blank=True, allow_null=True, default=None
    )

    def validate_environment(self, value: str) -> str:
        try:
            get_environment(value)
        except UnknownEnvironment as exc:
            raise serializers.ValidationError(str(exc)) from None
        return value

    def validate_event_timeline_end(self, value: float) -> float:
        if not math.isfinite(value) or value <= 0:
            raise serializers.ValidationError(f"must be a number > 0, got {value}")
        return value

    def validate_condition_at(self, value: float | None) -> float | None:
        # Upstream turned a negative value silently into a no-op; say so instead.
        if value is not None and (not math.isfinite(value) or value < 0):
            raise serializers.ValidationError(f"must be ≥ 0, or null for a no-op task; got {value}")
        return value

    def to_spec(self) -> dict:
        data = self.validated_data
        events = sorted(
            (
                {"time": e["time"], "type": e["type"], "payload": dict(e.get("payload") or {})}
                for e in data["events"]
            ),
            key=lambda e: e["time"],
        )  # stable sort, as upstream
        return {
            "id": f"init-{data['environment']}",
            "environment": data["environment"],
            "prompt": "",
            "start_page": data["start_page"] or "",
            "condition_at": data["condition_at"],
            "event_timeline_end": data["event_timeline_end"],
            "kill_at": data["event_timeline_end"],
            "events": events,
            "eval_sql": data["eval_sql"],
            "taxonomy": {},
            "annotator_notes": "",
            "solution": [],
            "is_dev": False,
            "source": "<init>",
        }


class RunCreateSerializer(serializers.Serializer):
    scenario = serializers.CharField(required=False, help_text="id of a scenario in the library")
    scenario_json = serializers.JSONField(required=False, help_text="a whole scenario, inline")
    speed_factor = serializers.FloatField(required=False, default=1.0, validators=[_speed_factor])
    clock_mode = serializers.ChoiceField(
        choices=ClockMode.choices, required=False, default=ClockMode.LIVE
    )

    def validate(self, attrs):
        given = [k for k in ("scenario", "scenario_json") if k in attrs]
        if len(given) != 1:
            raise serializers.ValidationError(
                {"scenario": "give exactly one of 'scenario' (an id) or 'scenario_json' (inline)"}
            )
        if "scenario" in attrs:
            attrs["spec"] = get_scenario(attrs["scenario"]).to_run_spec()
        else:
            try:
                attrs["spec"] = parse_scenario(
                    attrs["scenario_json"], source="scenario_json"
                ).to_run_spec()
            except ScenarioError as exc:
                raise serializers.ValidationError({"scenario_json": str(exc)}) from None
        if attrs["spec"]["environment"] not in environment_names():
            raise serializers.ValidationError(
                {
                    "scenario": f"environment {attrs['spec']['environment']!r} is not installed; "
                    f"valid: {', '.join(environment_names())}"
                }
            )
        return attrs


class AdvanceSerializer(serializers.Serializer):
    time = serializers.FloatField(help_text="simulated seconds on the authored scale")


class RunSerializer(serializers.ModelSerializer):
    task_url = serializers.SerializerMethodField()
    contact_url = serializers.SerializerMethodField()
    prompt = serializers.SerializerMethodField()
    sim_time = serializers.SerializerMethodField()

    class Meta:
        model = Run
        fields = [
            "id",
            "token",
            "scenario_id",
            "environment",
            "status",
            "clock_mode",
            "speed_factor",
            "sim_time",
            "prompt",
            "task_url",
            "contact_url",
            "catalog_hash",
            "created_at",
            "closed_at",
        ]

    def _absolute(self, path: str) -> str:
        request = self.context.get("request")
        return request.build_absolute_uri(path) if request else path

    def get_task_url(self, run: Run) -> str:
        return self._absolute(links.task_path(run))

    def get_contact_url(self, run: Run) -> str:
        return self._absolute(links.contact_path(run))

    def get_prompt(self, run: Run) -> str:
        return run.spec.get("prompt", "")

    def get_sim_time(self, run: Run) -> float:
        from events.clock import sim_now, wall_now

        return sim_now(run, wall_now())

"""Request and response shapes of the control plane."""

from __future__ import annotations

import math

from rest_framework import serializers

from apps.kit import links
from apps.scenarios.format import ScenarioError, parse_scenario, parse_timeline
from apps.scenarios.library import get_scenario
from events.models import ClockMode, Run
from events.registry import UnknownEnvironment, environment_names, get_environment
from events.timing import SpeedFactorError, validate_speed_factor

SCENARIO_ID_MAX = Run._meta.get_field("scenario_id").max_length


def _speed_factor(value: float) -> float:
    try:
        return validate_speed_factor(value)
    except SpeedFactorError as exc:
        raise serializers.ValidationError(str(exc)) from None


class FiniteFloatField(serializers.FloatField):
    """A number that is not NaN or infinite (DRF's FloatField takes "inf" and "1e400")."""

    def to_internal_value(self, data) -> float:
        value = super().to_internal_value(data)
        if not math.isfinite(value):
            raise serializers.ValidationError(f"must be a finite number, got {data!r}")
        return value


class InitPayloadSerializer(serializers.Serializer):
    """SentinelBench's `/init` body (extra keys such as kill_at, prompt, taxonomy are ignored)."""

    environment = serializers.CharField()
    event_timeline_end = FiniteFloatField()
    eval_sql = serializers.CharField(required=False, allow_blank=True, default="")
    condition_at = FiniteFloatField(required=False, allow_null=True, default=None)
    speed_factor = FiniteFloatField(required=False, default=1.0, validators=[_speed_factor])
    clock_mode = serializers.ChoiceField(  # ours: upstream has only the live clock
        choices=ClockMode.choices, required=False, default=ClockMode.LIVE
    )
    # [{time, type, payload}]: checked in validate() as a scenario file's timeline is.
    events = serializers.ListField(child=serializers.JSONField())
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

    def validate(self, attrs: dict) -> dict:
        # The one timeline validator (apps.scenarios.format): types and payloads against the
        # environment's schemas, so no accepted entry can break the run when it fires.
        try:
            attrs["events"] = parse_timeline(
                attrs["events"], attrs["environment"], source="/init", sort=True
            )  # a stable sort, as upstream
        except ScenarioError as exc:
            raise serializers.ValidationError({"events": str(exc)}) from None
        return attrs

    def to_spec(self) -> dict:
        data = self.validated_data
        events = list(data["events"])
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
    scenario = serializers.CharField(
        required=False,
        max_length=SCENARIO_ID_MAX,
        help_text="a scenario in the library: its id, or its file's path (microfy/x.json)",
    )
    scenario_json = serializers.JSONField(required=False, help_text="a whole scenario, inline")
    speed_factor = FiniteFloatField(required=False, default=1.0, validators=[_speed_factor])
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
            if len(attrs["spec"]["id"]) > SCENARIO_ID_MAX:
                raise serializers.ValidationError(
                    {"scenario_json": f"id: at most {SCENARIO_ID_MAX} characters"}
                )
        if attrs["spec"]["environment"] not in environment_names():
            raise serializers.ValidationError(
                {
                    "scenario": f"environment {attrs['spec']['environment']!r} is not installed; "
                    f"valid: {', '.join(environment_names())}"
                }
            )
        return attrs


class AdvanceSerializer(serializers.Serializer):
    time = FiniteFloatField(min_value=0, help_text="simulated seconds on the authored scale")


class RunSerializer(serializers.ModelSerializer):
    task_url = serializers.SerializerMethodField()
    contact_url = serializers.SerializerMethodField()
    wait_url = serializers.SerializerMethodField()
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
            "wait_url",
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

    def get_wait_url(self, run: Run) -> str:
        return self._absolute(links.wait_path(run))

    def get_prompt(self, run: Run) -> str:
        return run.spec.get("prompt", "")

    def get_sim_time(self, run: Run) -> float | None:
        from events.clock import sim_now, wall_now

        # A run's clock read as infinite (recorded before /advance refused it) must not make
        # the run list fail for every caller: it reads as unknown.
        now = sim_now(run, wall_now())
        return now if math.isfinite(now) else None

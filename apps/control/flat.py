"""SentinelBench-compatible flat endpoints on the single default slot (upstream-protocol.md §2).

Same paths, field names, state names and status codes as the original, with its listed
weaknesses fixed: contact times are floats, /advance is monotonic, `environment` is validated,
/scenarios/<id> hides the answer from unauthenticated callers and /redirect stays on our site.
Times in requests and responses are wall-scale seconds (authored ÷ speed_factor), as upstream.
"""

from __future__ import annotations

import math

from django.http import HttpResponseRedirect
from rest_framework import status as http
from rest_framework.decorators import api_view, permission_classes, throttle_classes
from rest_framework.permissions import AllowAny
from rest_framework.request import Request
from rest_framework.response import Response

from apps.control import accepted_inits, slot
from apps.control.auth import is_control_authenticated
from apps.control.parsers import request_data
from apps.control.serializers import InitPayloadSerializer
from apps.control.throttling import RunCreationThrottle
from apps.kit.links import start_page_path
from apps.scenarios.library import UnknownScenario, get_dev_scenario, get_scenario, scenario_library
from events import lifecycle
from events.catalog import load_catalog
from events.evaluation import evaluate as evaluate_run
from events.registry import environment_names
from events.timing import to_wall


def _status_body(run) -> dict:
    if run is None:
        return {"success": True, "status": "preinit", "simulation_time": 0, "next_event_time": None}
    # Every caller has just read the slot's run or written it (init, advance, play).
    snapshot = lifecycle.status_snapshot(run, reload=False)
    sf = run.speed_factor
    return {
        "success": True,
        "status": snapshot["status"],
        "simulation_time": round(to_wall(snapshot["sim_time"], sf), 2),
        "next_event_time": to_wall(snapshot["next_event_time"], sf),
    }


@api_view(["GET"])
def status(request: Request) -> Response:
    return Response(_status_body(slot.default_run()))


@api_view(["POST"])
@throttle_classes([RunCreationThrottle])  # a reset makes a run: counted as the API's are
def init(request: Request) -> Response:
    current = slot.default_run()
    if current is not None:
        raise lifecycle.LifecycleError(
            f"Wrong state: /init must be called in state 'preinit'. Current: '{current.status}'."
        )
    init = accepted_inits.accepted(request)
    if init is None:
        payload = InitPayloadSerializer(data=request_data(request))
        if not payload.is_valid():
            return Response(_one_line(payload.errors), status=http.HTTP_422_UNPROCESSABLE_ENTITY)
        init = accepted_inits.accept(
            request,
            payload.to_spec(),
            speed_factor=payload.validated_data["speed_factor"],
            clock_mode=payload.validated_data["clock_mode"],
        )
    run = slot.create_default_run(
        init.spec, speed_factor=init.speed_factor, clock_mode=init.clock_mode
    )
    return Response(_status_body(run))


@api_view(["GET"])
def advance(request: Request) -> Response:
    run = slot.require_default_run()  # "no session" is checked before the query, as upstream
    raw = request.query_params.get("time")
    try:
        wall_time = float(raw)
    except (TypeError, ValueError):
        wall_time = math.nan
    if not math.isfinite(wall_time):
        return Response(
            {
                "detail": "query parameter 'time' is required and must be a finite number, "
                f"got {raw!r}"
            },
            status=http.HTTP_422_UNPROCESSABLE_ENTITY,
        )
    fired = lifecycle.advance(run, wall_time * run.speed_factor)
    body = _status_body(run)
    body["simulation_time"] = wall_time
    body["processed_events"] = [
        {"time": to_wall(e.at, run.speed_factor), "type": e.type, "payload": e.payload}
        for e in fired.fired
    ]
    return Response(body)


@api_view(["GET"])
def play(request: Request) -> Response:
    run = lifecycle.start_clock(slot.require_default_run())
    return Response(_status_body(run))


@api_view(["GET"])
@permission_classes([AllowAny])  # the task URL is handed to the agent
def redirect(request: Request):
    run = lifecycle.start_clock(slot.require_default_run())
    # `frontend_url` is deliberately ignored: the run's pages live on this server, and
    # following a caller-supplied URL would be an open redirect.
    return HttpResponseRedirect(start_page_path(run))


@api_view(["POST"])
def evaluate(request: Request) -> Response:
    verdict = evaluate_run(slot.require_default_run()).as_dict()
    return Response(verdict)


@api_view(["GET"])
def close(request: Request) -> Response:
    slot.close_default_run()
    return Response({"success": True, "status": "preinit"})


@api_view(["POST"])
@throttle_classes([RunCreationThrottle])
def dev_init(request: Request) -> Response:
    environment = request.query_params.get("environment", "")
    if environment not in environment_names():
        return Response(
            {
                "detail": f"unknown environment {environment!r}; valid: {', '.join(environment_names())}"
            },
            status=http.HTTP_400_BAD_REQUEST,
        )
    try:
        spec = get_dev_scenario(environment).to_run_spec()
    except FileNotFoundError:
        return Response(
            {"detail": f"no dev.json for {environment}"}, status=http.HTTP_404_NOT_FOUND
        )
    slot.close_default_run()  # allowed from any state
    slot.create_default_run(spec, speed_factor=1.0)
    return Response({"success": True, "status": "ready", "environment": environment})


@api_view(["GET"])
@permission_classes([AllowAny])
def scenarios(request: Request) -> Response:
    return Response({"scenarios": sorted(scenario_library())})


PUBLIC_SCENARIO_FIELDS = ("id", "environment", "prompt", "start_page", "taxonomy")


@api_view(["GET"])
@permission_classes([AllowAny])
def scenario_detail(request: Request, scenario_id: str) -> Response:
    try:
        spec = get_scenario(scenario_id).to_run_spec()
    except UnknownScenario as exc:
        return Response({"detail": str(exc)}, status=http.HTTP_404_NOT_FOUND)
    if is_control_authenticated(request):
        return Response(spec)
    # Upstream served eval_sql, condition_at and the timeline to anyone, agents included.
    return Response({key: spec[key] for key in PUBLIC_SCENARIO_FIELDS})


@api_view(["GET"])
@permission_classes([AllowAny])
def data_config(request: Request) -> Response:
    run = slot.require_default_run()
    catalog = load_catalog(run.catalog_dir)
    return Response(
        {
            "environment": run.environment,
            "event_timeline_end": to_wall(run.event_timeline_end, run.speed_factor),
            "speed_factor": run.speed_factor,
            "selfUser": catalog.self_user,
        }
    )


@api_view(["GET"])
@permission_classes([AllowAny])
def data_users(request: Request) -> Response:
    return Response(list(load_catalog().users.values()))


def _one_line(errors) -> dict:
    parts = []
    for field, problems in errors.items():
        if isinstance(problems, list) and problems and isinstance(problems[0], dict):
            for index, item in enumerate(problems):
                for sub, msgs in (item or {}).items():
                    parts.append(f"{field}[{index}].{sub}: {' '.join(map(str, msgs))}")
        else:
            problems = problems if isinstance(problems, list) else [problems]
            parts.append(f"{field}: {' '.join(map(str, problems))}")
    return {"detail": "; ".join(parts), "errors": errors}

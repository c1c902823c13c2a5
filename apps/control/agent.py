"""Agent-facing run URLs: the task URL, the contact page, the JSON action endpoint and the
wait endpoint of fast-forward runs.

These need no control token: the unguessable run token in the path is the credential, and
none of them reveals scenario internals.
"""

from __future__ import annotations

import contextlib
import math

from django.core.exceptions import RequestDataTooBig
from django.http import HttpRequest, HttpResponse, HttpResponseRedirect, JsonResponse
from django.shortcuts import render
from django.views.decorators.csrf import csrf_exempt
from django.views.decorators.http import require_http_methods, require_POST

from apps.control import pace, slot
from apps.control.parsers import BadBody, body_limit, read_json
from apps.kit.links import contact_path, start_page_path
from apps.kit.live import last_live_seq
from apps.kit.log_payloads import ContactPost
from apps.kit.pages import arrival_wall, run_for_token
from events import fastforward, lifecycle
from events.clock import TICKING
from events.commands import current_folded, perform_action
from events.models import ClockMode, Run, RunStatus
from events.registry import ActionRejected
from events.schemas import PayloadError, validate_payload


@require_http_methods(["GET"])
def task_start(request: HttpRequest, token: str) -> HttpResponse:
    """Start the run's clock (first visit) and go to its start page; reloading is harmless."""
    run = run_for_token(token)
    if run.clock_mode in TICKING and run.status in lifecycle.CLOCK_STARTABLE:
        if run.clock_mode == ClockMode.FAST_FORWARD and pace.asked(request):
            return pace.hold_until(None)  # its clock starts when its turn comes
        # A concurrent first visit may have started it: then just go to the page.
        with contextlib.suppress(lifecycle.LifecycleError):
            run = lifecycle.start_clock(run)
    return HttpResponseRedirect(start_page_path(run))


def _contact(request: HttpRequest, run: Run, action: str) -> HttpResponse:
    wall = arrival_wall(request)  # the agent's moment of contact, not when a thread was free
    try:
        if request.method == "POST":
            message = request.POST.get("message", "")
            # Checked before the contact counts: the agent can send it again. Bounded as every
            # free text an agent writes (apps/kit/fields.py): 3 × 2 MB messages were stored.
            validate_payload(ContactPost, {"message": message}, what="contact")
            lifecycle.contact(run, method="POST", message=message, wall=wall)
            return render(request, "control/thanks.html", {"run": run})
        lifecycle.contact(run, method="GET", wall=wall)
    except PayloadError as exc:
        return JsonResponse({"detail": str(exc)}, status=400)
    except lifecycle.LifecycleError as exc:  # its log budget spent (429), as an action's
        return JsonResponse({"detail": str(exc)}, status=exc.status)
    return render(request, "control/contact.html", {"run": run, "action": action})


@csrf_exempt  # agents post this form from anywhere (curl, a browser); it carries no session
@require_http_methods(["GET", "POST"])
def run_contact(request: HttpRequest, token: str) -> HttpResponse:
    run = run_for_token(token)
    return _contact(request, run, contact_path(run))


@csrf_exempt
@require_http_methods(["GET", "POST"])
def flat_contact(request: HttpRequest) -> HttpResponse:
    run = slot.default_run()
    if run is None:
        return JsonResponse({"detail": slot.NO_SESSION}, status=409)
    return _contact(request, run, "/contact")


@csrf_exempt  # JSON API authenticated by the run token in the path
@require_POST
def run_action(request: HttpRequest, token: str) -> JsonResponse:
    """`POST {"action": name, "payload": {...}}`: the same actions the pages perform."""
    run = run_for_token(token)
    try:
        body = read_json(request.body or b"{}")
    except BadBody as exc:
        return JsonResponse({"detail": str(exc)}, status=400)
    except RequestDataTooBig:
        return JsonResponse({"detail": f"body is larger than {body_limit()} bytes"}, status=400)
    if not isinstance(body, dict) or not isinstance(body.get("action"), str):
        return JsonResponse(
            {"detail": 'body must be {"action": <name>, "payload": {...}}'}, status=400
        )
    payload = body.get("payload", {})
    if not isinstance(payload, dict):
        return JsonResponse({"detail": "payload must be an object"}, status=400)
    wall = arrival_wall(request)  # timed at its arrival, like page actions and contacts
    try:
        event, _ = perform_action(
            run,
            body["action"],
            payload,
            wall=wall,
            folded=current_folded(run, wall=wall, reload=False),
        )
    except ActionRejected as exc:
        return JsonResponse({"detail": str(exc)}, status=exc.status)
    return JsonResponse(
        {
            "seq": event.seq,
            "at": event.at,
            "action": event.type,
            "payload": event.payload,
            "run_status": RunStatus(run.status).value,
        },
        status=201,
    )


WAIT_SHAPE = (
    'body must be {"seconds": s}, {"to": t} or {"until": "change"} '
    '(with "timeout": s or "to": t, and "since": t)'
)
NUMBER_FIELDS = ("seconds", "timeout", "since", "to")  # simulated seconds, each ≥ 0


def wait_of(body: object) -> fastforward.Wait:
    """The wait a `/wait` body asks for; BadBody naming the field otherwise."""
    if not isinstance(body, dict):
        raise BadBody(WAIT_SHAPE)
    unknown = sorted(set(body) - {"until", *NUMBER_FIELDS})
    if unknown:
        raise BadBody(f"{unknown[0]}: unknown field; {WAIT_SHAPE}")
    if "until" in body and body["until"] != "change":
        raise BadBody(f'until: must be "change", got {body["until"]!r}')
    for name in NUMBER_FIELDS:
        value = body.get(name)
        if name in body and (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not (math.isfinite(value) and value >= 0)
        ):
            raise BadBody(f"{name}: must be a finite number of seconds ≥ 0, got {value!r}")
    if "until" not in body:
        for name in ("timeout", "since"):
            if name in body:
                raise BadBody(f'{name} goes with "until": a sleep has no {name}')
        if ("seconds" in body) == ("to" in body):
            raise BadBody(WAIT_SHAPE)
    elif "seconds" in body or ("timeout" in body and "to" in body):
        raise BadBody(WAIT_SHAPE)
    numbers = {name: float(body[name]) for name in NUMBER_FIELDS if name in body}
    return fastforward.Wait(until_change="until" in body, **numbers)


@csrf_exempt  # JSON API authenticated by the run token in the path
@require_POST
def run_wait(request: HttpRequest, token: str) -> JsonResponse:
    """`POST {"seconds": s}` or `{"until": "change", "timeout": s}` (or another shape of
    WAIT_SHAPE) on a fast_forward run: skip its clock ahead instead of sleeping; answers where
    the clock is now and what fired."""
    run = run_for_token(token)
    try:
        wait = wait_of(read_json(request.body or b"{}"))
    except BadBody as exc:
        return JsonResponse({"detail": str(exc)}, status=400)
    except RequestDataTooBig:
        return JsonResponse({"detail": f"body is larger than {body_limit()} bytes"}, status=400)
    if pace.asked(request):  # every awake place is taken: hold the wait back, if it is one
        refused = fastforward.refusal(run)
        if refused is not None:
            return JsonResponse({"detail": str(refused)}, status=refused.status)
        return pace.hold_until(fastforward.natural_end(run, wait, wall=arrival_wall(request)))
    try:
        skipped = fastforward.skip(
            run, wait, wall=arrival_wall(request), asked_at=pace.asked_at(request)
        )
    except lifecycle.LifecycleError as exc:
        return JsonResponse({"detail": str(exc)}, status=exc.status)
    return JsonResponse(
        {
            "from": skipped.start,
            "sim_time": skipped.end,
            "why": skipped.why,
            "fired": [{"at": event.at, "type": event.type} for event in skipped.fired],
            # The log position a page showing the new moment has reached at least (live
            # pages carry theirs in #sentinel-live[data-seq]).
            "seq": last_live_seq(run.pk),
            "speed_factor": run.speed_factor,
            "run_status": RunStatus(run.status).value,
        }
    )

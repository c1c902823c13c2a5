"""Multi-run API under /api/runs/: any number of concurrent, isolated runs."""

from __future__ import annotations

from drf_spectacular.utils import OpenApiParameter, extend_schema
from rest_framework import mixins, viewsets
from rest_framework import status as http
from rest_framework.decorators import action
from rest_framework.response import Response

from apps.control.pagination import NewestFirst, log_page
from apps.control.parsers import request_data
from apps.control.serializers import AdvanceSerializer, RunCreateSerializer, RunSerializer
from apps.control.throttling import RunCreationThrottle
from apps.replay.transfer import export_records
from apps.scenarios.library import get_scenario, library
from events import lifecycle
from events.evaluation import evaluate
from events.models import EVENT_FIELDS, Event, Run


class RunViewSet(mixins.ListModelMixin, mixins.RetrieveModelMixin, viewsets.GenericViewSet):
    queryset = Run.objects.all()
    serializer_class = RunSerializer
    pagination_class = NewestFirst

    def get_throttles(self):
        return [RunCreationThrottle()] if self.action == "create" else []

    def get_queryset(self):
        runs = super().get_queryset()
        if self.request.query_params.get("open") in ("1", "true"):
            runs = runs.filter(closed_at__isnull=True)
        return runs

    @extend_schema(request=RunCreateSerializer, responses={201: RunSerializer})
    def create(self, request):
        body = RunCreateSerializer(data=request_data(request))
        body.is_valid(raise_exception=True)
        run = lifecycle.create_run(
            body.validated_data["spec"],
            speed_factor=body.validated_data["speed_factor"],
            clock_mode=body.validated_data["clock_mode"],
        )
        return Response(self.get_serializer(run).data, status=http.HTTP_201_CREATED)

    def retrieve(self, request, pk=None):
        run = self.get_object()
        lifecycle.status_snapshot(run)  # fire what is due so the status is current
        return Response(self.get_serializer(run).data)

    @extend_schema(request=None, responses=RunSerializer)
    @action(detail=True, methods=["post"])
    def start(self, request, pk=None):
        run = lifecycle.start_clock(self.get_object())
        return Response(self.get_serializer(run).data)

    @extend_schema(request=AdvanceSerializer, responses=RunSerializer)
    @action(detail=True, methods=["post"])
    def advance(self, request, pk=None):
        body = AdvanceSerializer(data=request_data(request))
        body.is_valid(raise_exception=True)
        run = self.get_object()
        lifecycle.require_virtual_clock(run)
        fired = lifecycle.advance(run, body.validated_data["time"])
        data = self.get_serializer(run).data
        data["processed_events"] = [
            {"time": e.at, "type": e.type, "payload": e.payload} for e in fired.fired
        ]
        return Response(data)

    @extend_schema(request=None)
    @action(detail=True, methods=["post"])
    def evaluate(self, request, pk=None):
        return Response(evaluate(self.get_object()).as_dict())

    @extend_schema(request=None, responses=RunSerializer)
    @action(detail=True, methods=["post"])
    def close(self, request, pk=None):
        run = self.get_object()
        lifecycle.close(run)
        return Response(self.get_serializer(run).data)

    @extend_schema(request=None)
    @action(detail=True, methods=["get"])
    def events(self, request, pk=None):
        """The run's log, in order, enough to replay it: up to 10,000 entries a page (`?after=`
        the last seq seen, `?limit=`), the next page named in a `Link` header."""
        run = self.get_object()
        rows = Event.objects.filter(run_id=run.pk).order_by("seq").values(*EVENT_FIELDS)
        page, next_url = log_page(request, rows, request.path)
        response = Response(page)
        if next_url:
            response["Link"] = f'<{next_url}>; rel="next"'
        return response

    @extend_schema(request=None)
    @action(detail=True, methods=["get"])
    def export(self, request, pk=None):
        """The run as `export_run` writes it, one list item per line: a header (the run, its
        scenario and its recorded verdict), then every event. `import_run` reads it back."""
        run = self.get_object()
        return Response(list(export_records(run)))


class ScenarioViewSet(viewsets.ViewSet):
    """Scenario library for the control side (token-protected when a token is set).

    The list holds every file: a valid one with its id, a file repeating another's id with
    `duplicate_of` (run it by its `path`), and a file that failed validation with `error`
    and no id, so one bad file is reported instead of taking the library down.
    """

    serializer_class = None  # free-form scenario documents
    # A scenario is named by its id or by its file's path (microfy/x.json).
    lookup_value_regex = r"[^?#]+?"

    @extend_schema(operation_id="scenarios_list")
    def list(self, request):
        loaded = library()
        problems = {problem.path: problem for problem in loaded.problems}
        entries = []
        for path, scenario in loaded.by_path.items():
            entry = {
                "id": scenario.id,
                "path": path,
                "environment": scenario.environment,
                "noop": scenario.is_noop,
                "taxonomy": scenario.taxonomy,
            }
            if path in problems:
                entry["duplicate_of"] = problems[path].duplicate_of
                entry["problem"] = problems[path].detail
            entries.append(entry)
        entries += [
            {"id": None, "path": problem.path, "error": problem.detail}
            for problem in loaded.problems
            if problem.path not in loaded.by_path
        ]
        return Response(sorted(entries, key=lambda entry: entry["path"]))

    @extend_schema(parameters=[OpenApiParameter("id", str, OpenApiParameter.PATH)])
    def retrieve(self, request, pk=None):
        return Response(get_scenario(pk).to_run_spec())

"""Every error a caller can cause becomes `{"detail": "<one clear line>"}` with a 4xx status."""

from __future__ import annotations

from rest_framework import status as http
from rest_framework.response import Response
from rest_framework.views import exception_handler as drf_exception_handler

from apps.scenarios.format import ScenarioError
from apps.scenarios.library import UnknownScenario
from events.catalog import CatalogError
from events.lifecycle import LifecycleError
from events.registry import ActionRejected, UnknownEnvironment
from events.timing import SpeedFactorError

# Upstream answers validation problems with 422 (FastAPI/pydantic); we keep its codes.
_STATUS = {
    LifecycleError: None,  # carries its own status
    ActionRejected: None,
    SpeedFactorError: http.HTTP_422_UNPROCESSABLE_ENTITY,
    ScenarioError: http.HTTP_422_UNPROCESSABLE_ENTITY,
    UnknownEnvironment: http.HTTP_422_UNPROCESSABLE_ENTITY,
    UnknownScenario: http.HTTP_404_NOT_FOUND,
    CatalogError: http.HTTP_422_UNPROCESSABLE_ENTITY,
}


def exception_handler(exc, context):
    for kind, code in _STATUS.items():
        if isinstance(exc, kind):
            code = code or getattr(exc, "status", http.HTTP_400_BAD_REQUEST)
            return Response({"detail": str(exc)}, status=code)
    response = drf_exception_handler(exc, context)
    if response is not None and isinstance(response.data, dict) and "detail" not in response.data:
        # Serializer errors: flatten to one line naming each field.
        parts = []
        for field, problems in response.data.items():
            problems = problems if isinstance(problems, list) else [problems]
            parts.append(f"{field}: {' '.join(str(p) for p in problems)}")
        response.data = {"detail": "; ".join(parts), "errors": response.data}
    return response

"""Long lists a page at a time, still plain JSON lists: the run list (newest first) and a run's
log (in order).

`GET /api/runs/` answered every run ever made in one response. Now it answers at most `limit`
(default 100, at most 1,000); when there are more, a `Link: <…?before=<id>>; rel="next"` header
names the next page (as GitHub's API does), so a client reading the body as a list keeps
working and a client that wants everything follows the links. A cursor (`before`, the last id
seen) rather than an offset: runs created while paging never shift or repeat a page.
"""

from __future__ import annotations

from urllib.parse import urlencode

from rest_framework.exceptions import ValidationError
from rest_framework.pagination import BasePagination
from rest_framework.response import Response

DEFAULT_LIMIT = 100
MOST = 1_000


def whole_number(request, name: str, default: int | None, *, least: int, most: int | None):
    raw = request.query_params.get(name)
    if raw is None:
        return default
    try:
        value = int(raw)
    except ValueError:
        raise ValidationError({"detail": f"{name}={raw!r} is not a whole number"}) from None
    if value < least or (most is not None and value > most):
        bounds = f"from {least} to {most}" if most is not None else f"at least {least}"
        raise ValidationError({"detail": f"{name}={value} is out of range ({bounds})"})
    return value


class NewestFirst(BasePagination):
    def paginate_queryset(self, queryset, request, view=None):
        limit = whole_number(request, "limit", DEFAULT_LIMIT, least=1, most=MOST)
        before = whole_number(request, "before", None, least=1, most=None)
        if before is not None:
            queryset = queryset.filter(pk__lt=before)
        page = list(queryset.order_by("-pk")[: limit + 1])
        self.next_url = None
        if len(page) > limit:
            page = page[:limit]
            query = {**request.query_params.dict(), "before": page[-1].pk}
            self.next_url = request.build_absolute_uri(f"{request.path}?{urlencode(query)}")
        return page

    def get_paginated_response(self, data):
        response = Response(data)
        if self.next_url:
            response["Link"] = f'<{self.next_url}>; rel="next"'
        return response

    def get_paginated_response_schema(self, schema):
        return schema

    def get_schema_operation_parameters(self, view):
        return [
            {
                "name": "limit",
                "in": "query",
                "required": False,
                "description": f"runs per page, newest first (default {DEFAULT_LIMIT}, at most {MOST})",
                "schema": {"type": "integer"},
            },
            {
                "name": "before",
                "in": "query",
                "required": False,
                "description": "only runs with a smaller id (the next page: see the Link header)",
                "schema": {"type": "integer"},
            },
        ]


LOG_PAGE = 10_000  # entries of a run's log per page: all of nearly every run in one
LOG_MOST = 50_000


def log_page(request, rows, path: str) -> tuple[list[dict], str | None]:
    """One page of a run's log (`rows`: its events' values, by seq) from `?after=<seq>`, at most
    `?limit=` entries, and the next page's URL (None: this was the last)."""
    limit = whole_number(request, "limit", LOG_PAGE, least=1, most=LOG_MOST)
    after = whole_number(request, "after", 0, least=0, most=None)
    page = list(rows.filter(seq__gt=after)[: limit + 1])
    if len(page) <= limit:
        return page, None
    page = page[:limit]
    query = {**request.query_params.dict(), "after": page[-1]["seq"]}
    return page, request.build_absolute_uri(f"{path}?{urlencode(query)}")

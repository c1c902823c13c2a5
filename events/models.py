"""Run and Event: the only authoritative data. Everything else is derived by folding."""

from __future__ import annotations

import datetime
import functools
import secrets
from collections.abc import Callable
from typing import Any, cast

from django.db import DEFAULT_DB_ALIAS, connections, models
from django.db.models import Q

from events.lru import LRU


def column_field(model: type[models.Model], name: str) -> models.Field[Any, Any]:
    """`model._meta.get_field(name)` for the name of a field stored in the model's own table.

    get_field is typed for any name, which may also be a reverse relation or a generic foreign
    key (neither has a column); the callers name concrete fields."""
    return cast("models.Field[Any, Any]", model._meta.get_field(name))


def new_run_token() -> str:
    return secrets.token_urlsafe(24)


# Keyed by (pk, token): a rolled-back transaction (tests) can hand a pk to another run.
_spec_cache: LRU[tuple[int, str], dict] = LRU(4096)


class RunStatus(models.TextChoices):
    # The exact SentinelBench state names (upstream-protocol.md §1); `preinit` is the absence
    # of an open run in the default slot, so it is not a run status.
    READY = "ready"
    RUNNING_AUTO = "running_auto"
    RUNNING_MANUAL = "running_manual"
    COMPLETED = "completed"


class ClockMode(models.TextChoices):
    LIVE = "live"  # sim = (wall − started_at) × speed_factor once started
    VIRTUAL = "virtual"  # moved only by advance
    # Live, plus skips: the agent's declared waits jump the clock ahead (events.fastforward).
    FAST_FORWARD = "fast_forward"


class RunQuerySet(models.QuerySet):
    def open_by_token(self, token: str) -> Run | None:
        """The open run with this token, or None: what every /r/<token>/ request starts from.

        Every agent page and live push makes this read, so it skips the ORM's per-call query
        building (about 300 µs, against 20 µs for the read itself) for SQL written once per
        database. The scenario column stays deferred (read it through `Run.spec`, cached per
        process): it holds the whole timeline, and decoding it on every request was wasted.
        """
        return self._open_run("{token} = %s", [token])

    def open_default(self) -> Run | None:
        """The open run of the default slot (the flat endpoints' one session), or None: read
        by every /status, /init, /evaluate and /close, so written once, like `open_by_token`.
        The condition is the partial unique index's own, so SQLite reads the index instead of
        scanning every run ever created (`is_default_slot = 1` does not imply it)."""
        return self._open_run("{is_default_slot}", [])

    def _open_run(self, condition: str, params: list[Any]) -> Run | None:
        # The row made into a model as a raw queryset would, without its per-call work of
        # matching columns to fields (three quarters of the read).
        sql, names, converters = _open_run_plan(self.db, condition)
        with connections[self.db].cursor() as cursor:
            cursor.execute(sql, params)
            row = cursor.fetchone()
        if row is None:
            return None
        values = [convert(value) for convert, value in zip(converters, row, strict=True)]
        return Run.from_db(self.db, names, values)


@functools.cache
def _open_run_plan(alias: str, condition: str) -> tuple[str, list[str], list[Callable[[Any], Any]]]:
    quote = connections[alias].ops.quote_name
    fields = [field for field in Run._meta.concrete_fields if field.name != "scenario"]
    columns = ", ".join(quote(field.column) for field in fields)
    where = condition.format(token=quote("token"), is_default_slot=quote("is_default_slot"))
    sql = (
        f"SELECT {columns} FROM {quote(Run._meta.db_table)} "
        f"WHERE {where} AND {quote('closed_at')} IS NULL"
    )
    return sql, [field.attname for field in fields], _converters(alias, fields)


@functools.cache
def _reread_plan(alias: str, names: tuple[str, ...]) -> tuple[str, list[Callable[[Any], Any]]]:
    """`Run.reread`'s SQL for `names`."""
    quote = connections[alias].ops.quote_name
    fields = [column_field(Run, name) for name in names]
    columns = ", ".join(quote(field.column) for field in fields)
    sql = f"SELECT {columns} FROM {quote(Run._meta.db_table)} WHERE {quote('id')} = %s"
    return sql, _converters(alias, fields)


def _converters(alias: str, fields: list[models.Field[Any, Any]]) -> list[Callable[[Any], Any]]:
    """Per field, the conversion the ORM applies to what the database returns for it (a
    datetime made aware, for one)."""
    connection = connections[alias]

    def converter(field: models.Field[Any, Any]) -> Callable[[Any], Any]:
        column = field.cached_col
        # Field.get_db_converters is public Django, missing from the stubs.
        own = cast(Any, field).get_db_converters(connection)
        steps = connection.ops.get_db_converters(column) + own

        def convert(value: Any) -> Any:
            for step in steps:
                value = step(value, column, connection)
            return value

        return convert

    return [converter(field) for field in fields]


@functools.cache
def _complete_sql(alias: str) -> str:
    quote = connections[alias].ops.quote_name
    status = quote("status")
    return (
        f"UPDATE {quote(Run._meta.db_table)} SET {status} = %s, {quote('sim_time')} = %s "
        f"WHERE {quote('id')} = %s AND {status} <> %s"
    )


@functools.cache
def _close_sql(alias: str) -> str:
    quote = connections[alias].ops.quote_name
    closed_at = quote("closed_at")
    return (
        f"UPDATE {quote(Run._meta.db_table)} "
        f"SET {closed_at} = COALESCE({closed_at}, %s) WHERE {quote('id')} = %s "
        f"RETURNING {quote('status')}, {quote('sim_time')}, {closed_at}"
    )


class Run(models.Model):
    """One playback of one scenario for one agent.

    The clock lives here so that every process (web worker, Celery worker, a restarted server)
    computes the same simulated time. Wall times are float epoch seconds.
    """

    token = models.CharField(max_length=64, unique=True, default=new_run_token, editable=False)
    scenario_id = models.CharField(max_length=200, db_index=True)
    environment = models.CharField(max_length=64)
    # The validated scenario as played (timeline, eval_sql, condition_at, …): a run keeps
    # working even if the scenario file changes afterwards.
    scenario = models.JSONField()
    speed_factor = models.FloatField(default=1.0)
    clock_mode = models.CharField(max_length=16, choices=ClockMode.choices, default=ClockMode.LIVE)
    status = models.CharField(max_length=32, choices=RunStatus.choices, default=RunStatus.READY)
    started_at = models.FloatField(
        null=True, blank=True, help_text="wall epoch seconds at sim time 0"
    )
    sim_time = models.FloatField(
        default=0.0, help_text="virtual clock value; the frozen time once completed"
    )
    skipped = models.FloatField(
        default=0.0, help_text="simulated seconds skipped by the agent's waits (fast_forward)"
    )
    catalog_dir = models.CharField(max_length=500)
    catalog_hash = models.CharField(max_length=64)
    is_default_slot = models.BooleanField(default=False)
    created_at = models.DateTimeField(auto_now_add=True)
    closed_at = models.DateTimeField(null=True, blank=True)

    objects = RunQuerySet.as_manager()

    class Meta:
        ordering = ["-id"]
        constraints = [
            models.UniqueConstraint(
                fields=["is_default_slot"],
                condition=Q(is_default_slot=True, closed_at__isnull=True),
                name="one_open_default_run",
            )
        ]
        indexes = [models.Index(fields=["status", "closed_at"])]

    def __str__(self) -> str:
        return f"run {self.pk} · {self.scenario_id} · {self.status}"

    @property
    def spec(self) -> dict:
        """The scenario as played. Immutable per run, so hot paths (the ticker) defer the
        column and read it from a per-process cache instead of decoding JSON every tick."""
        if "scenario" not in self.get_deferred_fields():
            return self.scenario
        key = (self.pk, self.token)
        spec = _spec_cache.get(key)
        if spec is None:  # another process created the run, or this one forgot it
            spec = Run.objects.filter(pk=self.pk).values_list("scenario", flat=True).get()
            _spec_cache.put(key, spec)
        return spec

    def reread(self, *names: str) -> None:
        """Read the fields `names` again from the database (they move while the run lives: its
        clock, `closed_at`), as `refresh_from_db(fields=names)` would. Every `/status`, page and
        evaluation re-reads the clock before firing, so the SQL and the value converters are
        made once per database and field set: the ORM's per-call building was ten times the
        read itself."""
        alias = self._state.db or DEFAULT_DB_ALIAS
        sql, converters = _reread_plan(alias, names)
        with connections[alias].cursor() as cursor:
            cursor.execute(sql, [self.pk])
            row = cursor.fetchone()
        if row is None:
            raise Run.DoesNotExist(f"run {self.pk} no longer exists")
        for name, convert, value in zip(names, converters, row, strict=True):
            setattr(self, name, convert(value))

    def complete_at(self, sim_time: float) -> bool:
        """Complete the run with its clock frozen at `sim_time`, unless it is completed already
        (a conditional write: one caller wins); True when this call completed it. Every
        /evaluate does it: SQL written once, as `reread`."""
        alias = self._state.db or DEFAULT_DB_ALIAS
        with connections[alias].cursor() as cursor:
            completed = RunStatus.COMPLETED.value
            cursor.execute(_complete_sql(alias), [completed, sim_time, self.pk, completed])
            if cursor.rowcount != 1:
                return False
        self.status, self.sim_time = RunStatus.COMPLETED, sim_time
        return True

    def close_once(self, when: datetime.datetime) -> None:
        """Set `closed_at` to `when` unless the run is closed already, and read back its status,
        clock and `closed_at` as they then stand — one statement, on every /close."""
        alias = self._state.db or DEFAULT_DB_ALIAS
        connection = connections[alias]
        closed_at = column_field(Run, "closed_at")
        with connection.cursor() as cursor:
            cursor.execute(
                _close_sql(alias), [closed_at.get_db_prep_save(when, connection), self.pk]
            )
            row = cursor.fetchone()
        if row is None:
            raise Run.DoesNotExist(f"run {self.pk} no longer exists")
        names = ("status", "sim_time", "closed_at")
        _, converters = _reread_plan(alias, names)
        for name, convert, value in zip(names, converters, row, strict=True):
            setattr(self, name, convert(value))

    def remember_spec(self) -> None:
        """Keep the scenario this process just wrote, so its deferred reads cost no query."""
        _spec_cache.put((self.pk, self.token), self.scenario)

    def forget_spec(self) -> None:
        """A closed run is never read again on the hot paths: its scenario need not be kept."""
        _spec_cache.pop((self.pk, self.token))

    @property
    def event_timeline_end(self) -> float:
        return float(self.spec["event_timeline_end"])

    @property
    def condition_at(self) -> float | None:
        return self.spec.get("condition_at")

    @property
    def timeline(self) -> list[dict]:
        return self.spec["events"]

    @property
    def is_closed(self) -> bool:
        return self.closed_at is not None


class EventKind(models.TextChoices):
    SCENARIO = "scenario"
    ACTION = "action"
    VIEW = "view"
    LIFECYCLE = "lifecycle"


# The lifecycle entries the agent writes: its contacts, by GET (a visit) and by POST (the form).
CONTACT_GET, CONTACT_POST = "contact_get", "contact_post"


class AppendOnlyQuerySet(models.QuerySet):
    def update(self, **kwargs):
        raise PermissionError("events are append-only: a logged event is never updated")

    def delete(self):
        raise PermissionError("events are append-only: a logged event is never deleted")


# Every field of a logged event but its run: what an export, the API and a replay carry.
EVENT_FIELDS = (
    "seq",
    "at",
    "kind",
    "type",
    "payload",
    "recorded_at",
    "timeline_index",
    "lateness_ms",
)


class Event(models.Model):
    """One row of a run's log. Never updated, never deleted while its run exists."""

    run = models.ForeignKey(Run, on_delete=models.CASCADE, related_name="events")
    seq = models.PositiveIntegerField()
    at = models.FloatField(help_text="simulated seconds, authored scale")
    kind = models.CharField(max_length=16, choices=EventKind.choices)
    type = models.CharField(max_length=64)
    payload = models.JSONField(default=dict)
    recorded_at = models.FloatField(help_text="wall epoch seconds")
    timeline_index = models.PositiveIntegerField(null=True, blank=True)
    lateness_ms = models.FloatField(
        null=True, blank=True, help_text="wall time recorded − wall time due (live clock only)"
    )

    objects = AppendOnlyQuerySet.as_manager()

    class Meta:
        ordering = ["run_id", "seq"]
        constraints = [
            models.UniqueConstraint(fields=["run", "seq"], name="event_unique_seq"),
            models.UniqueConstraint(
                fields=["run", "timeline_index"],
                condition=Q(timeline_index__isnull=False),
                name="event_timeline_entry_fires_once",
            ),
        ]
        # Live pages ask for the last scenario/action event of a run; without this, that walks
        # every page view the run has logged.
        indexes = [models.Index(fields=["run", "kind", "seq"], name="event_run_kind_seq")]

    def __str__(self) -> str:
        return f"#{self.seq} @{self.at:.2f} {self.kind}:{self.type}"

    def save(self, *args, **kwargs):
        if not self._state.adding:
            raise PermissionError("events are append-only: a logged event is never updated")
        super().save(*args, **kwargs)

    def delete(self, *args, **kwargs):
        raise PermissionError("events are append-only: a logged event is never deleted")

"""MicroLendar pages: thin views over `page.state`, actions through `page.act`.

Every view serves the full page, or just the `#calendar-app` content when htmx asks for a
fragment (apps.kit.rendering). Actions are POST forms that come back to the screen they
came from (the `back` field; post/redirect/get), so the site works with plain links and forms;
htmx and the drag-and-drop script only make it smoother. Opening an event's details marks it
viewed: declared with the environment (`implicit_actions`).
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

from django.http import Http404, HttpRequest, HttpResponse
from django.views.decorators.http import require_http_methods

from apps.kit import simclock
from apps.kit.pages import Page, form_view, one_of, run_page, screen_view
from apps.kit.rendering import redirect_after, render_screen
from apps.microlendar import screens, times
from apps.microlendar.actions import DEFAULT_START, EVENT_FIELDS, existing_event
from apps.microlendar.query import VIEW_TITLES, VIEWS, CalendarQuery
from apps.microlendar.state import (
    CALENDAR_COLORS,
    CALENDARS,
    Agenda,
    CalendarEvent,
    conflicts_with,
    guests,
)
from events.registry import ActionRejected

DONE = {"reschedule": "Event rescheduled", "delete": "Event deleted"}
EVENT_ACTIONS = {"reschedule": "reschedule_event", "delete": "delete_event"}
TASK_ACTIONS = {"toggle": "toggle_task", "delete": "delete_task"}
TICKED = {True: "Task completed", False: "Task marked not done"}  # what a toggle led to


def calendar_moment(agenda: Agenda, page: Page) -> datetime:
    """The page's simulated moment on the calendar: simulated second 0 is 09:00 (simclock) on the
    day the scenario opens on (`initial_date`, else `today`, else the run's day zero), so "today"
    and the current-time line move as the shell's time does, past midnight to the next day. The
    page is pushed again next minute."""
    page.changes_at(simclock.next_minute(page.now))
    start = agenda.initial_date or agenda.today or simclock.day_zero(page.run)
    return simclock.moment(page.now, start)


def base_context(page: Page, query: CalendarQuery) -> dict:
    """What the chrome (top bar, sidebar) of every screen needs."""
    agenda: Agenda = page.state
    moment = calendar_moment(agenda, page)
    today = moment.date()
    shown = query.shown_date(today)
    return {
        "query": query,
        "moment": moment,
        "today": today,
        "shown": shown,
        "self_name": agenda.self_name,
        "self_email": agenda.self_email,
        "views": [
            (v, VIEW_TITLES[v], query.on(shown, today, view=v).querystring() or "?") for v in VIEWS
        ],
        "mini": screens.mini_month(agenda, query.but(q="", event=None), shown, today),
        # (name, color, shown, the screen with it toggled) per calendar of "My calendars"
        "calendars": [
            (name, CALENDAR_COLORS[name], name not in query.hidden, query.toggling(name))
            for name in CALENDARS
        ],
        "tasks": screens.task_rows(agenda, today),
        "invitations": screens.invitation_rows(agenda, query.but(q="", event=None)),
        "back": query.querystring(),
        "calendar_choices": CALENDARS,
    }


@screen_view
def calendar(request: HttpRequest, page: Page) -> HttpResponse:
    """The calendar in the chosen view, with event `event=<id>` open (which marks it viewed)."""
    query = CalendarQuery.from_params(request.GET)
    agenda: Agenda = page.state
    # Unknown, deleted, or not on the calendar yet: alike. A cancelled one stays open, saying so.
    if query.event is not None and not (
        agenda.has_event(query.event) or agenda.cancelled(query.event)
    ):
        raise Http404("no such event")
    context = base_context(page, query)
    screen = screens.calendar_screen(agenda, query, context["today"])
    opened = agenda.events[query.event] if query.event else None
    context.update(
        screen=screen,
        now_top=screens.now_line_top(context["moment"]),
        details=opened,
        guests=guests(agenda, opened) if opened else (),
        conflicts=conflicts_with(agenda, opened) if opened and agenda.has_event(opened.id) else (),
        close_url=query.but(event=None).querystring() or "?",
        clear_search_url=query.but(q="", event=None).querystring() or "?",
        title_for_tab=screen.title,
    )
    return render_screen(request, page, "microlendar/calendar.html", context)


# --- creating and editing events ---------------------------------------------------------------


@dataclass(frozen=True)
class EventForm:
    """The fields of the event form as shown (prefilled, or as typed when refused)."""

    title: str = ""
    date: str = ""
    time: str = DEFAULT_START
    endTime: str = "10:00"
    calendar: str = "Work"
    description: str = ""
    location: str = ""
    event_id: str | None = None

    @classmethod
    def typed(cls, request: HttpRequest, **extra) -> EventForm:
        fields = {name: request.POST.get(name, "").strip() for name in EVENT_FIELDS}
        return cls(**fields, **extra)

    @classmethod
    def of(cls, event: CalendarEvent) -> EventForm:
        """The form of an event as it stands (what the edit form starts from)."""
        fields = {
            name: write(getattr(event, attr)) for name, (attr, _, write) in EVENT_FIELDS.items()
        }
        return cls(**fields, event_id=event.id)

    def payload(self) -> dict:
        return {name: getattr(self, name) for name in EVENT_FIELDS if getattr(self, name) != ""}


def new_event_form(request: HttpRequest, today) -> EventForm:
    """Prefilled from the link that opened it: `date`, `time` (a clicked slot), `kind=reminder`
    (upstream's reminder: an event in Personal described "Reminder")."""
    day = request.GET.get("date") or today.isoformat()
    start = request.GET.get("time") or DEFAULT_START
    try:
        end = times.hhmm(min(times.parse_clock(start) + 60, 24 * 60 - 1))
    except times.BadTime:
        start, end = DEFAULT_START, "10:00"
    reminder = request.GET.get("kind") == "reminder"
    kind = {"calendar": "Personal", "description": "Reminder"} if reminder else {}
    return EventForm(date=day, time=start, endTime=end, **kind)


def render_form(
    request: HttpRequest, page: Page, form: EventForm, *, error: str = "", status: int = 200
) -> HttpResponse:
    back = CalendarQuery.from_querystring(request.POST.get("back") or request.GET.get("back", ""))
    context = {
        **base_context(page, back),
        "form": form,
        "error": error,
        "cancel_url": back.querystring() or "?",
    }
    return render_screen(request, page, "microlendar/event_form.html", context, status=status)


def after_save(request: HttpRequest, page: Page, day: str, done: str) -> HttpResponse:
    """Back to the screen the form came from, moved to the event's day."""
    return redirect_after(
        request, page, _back(request).but(date=day, event=None).querystring(), done
    )


@require_http_methods(["GET", "POST"])
@run_page
def new_event(request: HttpRequest, page: Page) -> HttpResponse:
    if request.method == "GET":
        today = calendar_moment(page.state, page).date()
        return render_form(request, page, new_event_form(request, today))
    form = EventForm.typed(request)
    try:
        event = page.act("create_event", form.payload())
    except ActionRejected as exc:
        return render_form(request, page, form, error=str(exc), status=exc.status)
    return after_save(request, page, event.payload["date"], f"“{event.payload['title']}” saved")


@require_http_methods(["GET", "POST"])
@run_page
def edit_event(request: HttpRequest, page: Page, event_id: str) -> HttpResponse:
    current = existing_event(page.state, event_id)
    original = EventForm.of(current)
    if request.method == "GET":
        return render_form(request, page, original)
    form = EventForm.typed(request, event_id=event_id)
    # Only what was changed is sent (an emptied description is a change; an unchanged time is not).
    changes = {
        name: getattr(form, name)
        for name in EVENT_FIELDS
        if getattr(form, name) != getattr(original, name)
    }
    try:
        event = page.act("update_event", {"event_id": event_id, **changes})
    except ActionRejected as exc:
        return render_form(request, page, form, error=str(exc), status=exc.status)
    day = event.payload.get("date", current.day.isoformat())
    return after_save(request, page, day, "Event updated")


# --- acting on an event, on tasks ----------------------------------------------------------------


@form_view
def event_action(request: HttpRequest, page: Page, event_id: str, action: str) -> HttpResponse:
    """`POST events/<id>/reschedule` (date, time: the form and a drag send the same) and
    `POST events/<id>/delete`, then back to the screen."""
    one_of(action, EVENT_ACTIONS, "event action")
    payload = {"event_id": event_id}
    if action == "reschedule":
        payload["date"] = request.POST.get("date", "")
        if request.POST.get("time"):
            payload["time"] = request.POST["time"]
    page.act(EVENT_ACTIONS[action], payload)
    back = _back(request).but(event=None) if action == "delete" else _back(request)
    return redirect_after(request, page, back.querystring(), DONE[action])


@form_view
def new_task(request: HttpRequest, page: Page) -> HttpResponse:
    payload = {"title": request.POST.get("title", "")}
    if request.POST.get("dueDate"):
        payload["dueDate"] = request.POST["dueDate"]
    page.act("create_task", payload)
    return redirect_after(request, page, _back(request).querystring(), "Task created")


@form_view
def task_action(request: HttpRequest, page: Page, task_id: str, action: str) -> HttpResponse:
    one_of(action, TASK_ACTIONS, "task action")
    event = page.act(TASK_ACTIONS[action], {"task_id": task_id})
    done = "Task deleted" if action == "delete" else TICKED[event.payload["completed"]]
    return redirect_after(request, page, _back(request).querystring(), done)


def _back(request: HttpRequest) -> CalendarQuery:
    """The screen a form came from (its `back` field)."""
    return CalendarQuery.from_querystring(request.POST.get("back", ""))

"""MicroChat pages over a run of our payment scenario (virtual clock): what each screen shows,
what is hidden until its event fires, and the forms that act."""

from __future__ import annotations

from pathlib import Path

import pytest
from django.conf import settings
from django.test import Client

from apps.kit.probe import probe_run, render_probe, state_at_time
from apps.kit.visible import visible_text
from apps.microchat import screens
from apps.microchat.markup import render_markup
from apps.scenarios.format import load_scenario_file
from events import lifecycle
from events.commands import current_state
from events.models import ClockMode, Event, EventKind

pytestmark = pytest.mark.django_db

PAYMENTS_AT = 534.0
PAYMENTS_TEXT = "card payments are failing"


@pytest.fixture
def run():
    path = Path(settings.SENTINEL_SCENARIO_DIR) / "microchat" / "payment-absolute-active.json"
    return lifecycle.create_run(
        load_scenario_file(path).to_run_spec(), clock_mode=ClockMode.VIRTUAL
    )


@pytest.fixture
def get(run):
    client = Client()

    def get(path: str = "", status: int = 200) -> str:
        response = client.get(f"/r/{run.token}/microchat/{path}")
        assert response.status_code == status, response.content[:300]
        return response.content.decode()

    get.client = client
    return get


def actions(run) -> list[str]:
    return list(Event.objects.filter(run=run, kind=EventKind.ACTION).values_list("type", flat=True))


def test_a_message_is_nowhere_until_its_event_fires(run, get):
    for path in ("", "?conversation=direct-gabriel", "search?q=card+payments"):
        assert PAYMENTS_TEXT not in get(path)
    lifecycle.advance(run, PAYMENTS_AT)
    assert PAYMENTS_TEXT in get("search?q=card+payments")
    listing = get()
    assert "Unread: </span>Gabriel Nwosu" in listing
    assert "Heads up: card payments are failing" in listing  # the row's preview


def test_opening_a_chat_reads_it_once_and_shows_the_urgent_marker(run, get):
    lifecycle.advance(run, PAYMENTS_AT)
    page = get("?conversation=direct-gabriel")
    assert "URGENT!" in page and PAYMENTS_TEXT in page
    assert current_state(run).read["urg-gabriel-09"] is True
    get("?conversation=direct-gabriel")  # a reload changes nothing
    assert actions(run) == ["open_conversation"]


def test_screens_and_their_errors(get):
    assert "Favorites" in get() and "Sharing Squad" in get()
    assert "Meeting chat" in get("?filter=meetings")
    assert "Platform Engineering" in get("teams")
    assert "Incidents" in get("teams/team-platform/ch-platform-incidents")
    assert "Missed" in get("calls?filter=missed")
    assert "Work week" in get("calendar") and "Sharing Sprint Planning" in get("calendar")
    get("?conversation=direct-nobody", status=404)
    get("teams/team-nope", status=404)
    get("?filter=starred", status=400)


def test_the_star_and_the_composer_act_and_come_back(run, get):
    client = get.client
    get()  # a page first: the session and CSRF cookie, as a browser has them
    root = f"/r/{run.token}/microchat/"
    response = client.post(
        root + "conversations/pin", {"conversation_id": "direct-noor", "back": ""}
    )
    assert response.status_code == 302 and response["Location"] == root
    response = client.post(
        root + "send",
        {
            "conversation_id": "direct-noor",
            "content": "Thanks **Noor**!",
            "back": "?conversation=direct-noor",
        },
    )
    assert response.status_code == 302
    page = get("?conversation=direct-noor")
    assert "Thanks <strong>Noor</strong>!" in page
    assert "Remove Noor Haddad from Favorites" in get()
    assert actions(run) == ["pin", "send_message"]


def test_light_markdown_escapes_and_highlights_mentions_of_me():
    html = render_markup(
        "**Hi** @Chris Taylor and @Maya, see `code` <b>x</b> https://x.example/a.",
        ("Chris Taylor", "Chris"),
    )
    assert "<strong>Hi</strong>" in html and "<code>code</code>" in html
    assert '<span class="mention me">@Chris Taylor</span>' in html
    assert '<span class="mention">@Maya</span>' in html
    assert "&lt;b&gt;x&lt;/b&gt;" in html
    assert 'href="https://x.example/a"' in html and "</a>." in html
    assert '<span class="mention me">@Sam</span>' in render_markup("@you", ("Sam",))


def test_the_activity_feed_reads_newest_first_and_never_later_than_now():
    """Regression: Activity listed reactions at "14:35" at 09:02, above calls of "Yesterday"
    (past days' times shown as today's, preloaded calls sorted apart from the rest)."""
    dev = load_scenario_file(Path(settings.SENTINEL_SCENARIO_DIR) / "microchat" / "dev.json")
    now = 120.0
    chat = state_at_time("microchat", dev.events, now)
    items = screens.activity(chat, "/")
    times = [item.at for item in items]
    assert None not in times and times == sorted(times, reverse=True)
    assert max(times) <= now
    text = visible_text(
        render_probe(probe_run("microchat", dev.to_run_spec()), chat, now, "activity")
    )
    assert "Missed call 31 min ago" in text and "Yesterday 16:00" in text

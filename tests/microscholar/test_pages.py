"""MicroScholar pages over a run of our search-and-cite scenario (virtual clock): what each screen
shows, what stays hidden until its event fires, and the forms and dialog that act."""

from __future__ import annotations

from pathlib import Path

import pytest
from django.conf import settings
from django.test import Client

from apps.scenarios.format import load_scenario_file
from events import lifecycle
from events.commands import current_state
from events.models import ClockMode, Event, EventKind
from tests.microscholar.cast import CAST, TARGET

pytestmark = pytest.mark.django_db

TARGET_AT = 12.0
FIRST = "paper-021"  # "Faithfulness Checks for Abstractive Meeting Summaries", preloaded


@pytest.fixture
def run():
    path = Path(settings.SENTINEL_SCENARIO_DIR) / "microscholar" / "search-absolute-active.json"
    return lifecycle.create_run(
        load_scenario_file(path).to_run_spec(), clock_mode=ClockMode.VIRTUAL
    )


@pytest.fixture
def client():
    return Client()


@pytest.fixture
def get(run, client):
    def get(path: str = "", status: int = 200) -> str:
        response = client.get(f"/r/{run.token}/microscholar/{path}")
        assert response.status_code == status, response.content[:300]
        return response.content.decode()

    return get


def actions(run) -> list[tuple[str, dict]]:
    return [
        (e.type, e.payload)
        for e in Event.objects.filter(run=run, kind=EventKind.ACTION).order_by("seq")
    ]


def test_home_recommends_what_is_indexed_and_the_target_appears_when_its_event_fires(run, get):
    home = get()
    assert "Recommended articles" in home and "20 articles" in home
    assert "Deliberate Delegation" not in home
    get(f"papers/{TARGET}", status=404)
    title = "Deliberate Delegation: Language Agents"
    assert title not in get("?q=Deliberate+Delegation")
    lifecycle.advance(run, TARGET_AT)
    assert title in get("?q=Deliberate+Delegation")
    home = get()
    assert home.index(f'id="t-{TARGET}"') == home.index('id="t-')  # newest indexed first


def test_results_page_has_filters_sorts_and_the_action_row(get):
    page = get("?q=summaries")
    for text in (
        "Any time",
        "Since ",
        "Custom range",
        "Sort by relevance",
        "Sort by date",
        "Cited by ",
        "Related articles",
        "versions",
    ):
        assert text in page
    assert 'data-action="save"' in page
    get("?q=x&as_ylo=last+year", status=400)


def test_opening_the_cite_dialog_cites_once_and_shows_five_styles(run, get):
    dialog = get(f"papers/{FIRST}/cite")
    for style in ("MLA", "APA", "Chicago", "Harvard", "BibTeX", "EndNote", "RefMan", "RefWorks"):
        assert f">{style}<" in dialog
    get(f"papers/{FIRST}/cite")  # reopening records nothing more
    assert actions(run) == [("cite", {"paper_id": FIRST})]
    assert current_state(run).is_cited(FIRST)
    bib = get(f"papers/{FIRST}/export/bibtex")
    assert bib.startswith("@inproceedings{tanabe2021faithfulness")


def test_save_from_a_result_then_remove_from_the_library(run, client, get):
    root = f"/r/{run.token}/microscholar/"
    get()  # a page view first, so the form carries a CSRF cookie
    response = client.post(root + "library/save", {"paper_id": FIRST, "back": "?q=threads"})
    assert response.status_code == 302 and response["Location"].endswith("/microscholar/?q=threads")
    library = get("library")
    assert "Faithfulness Checks for Abstractive" in library and "1 article" in library
    client.post(root + "library/remove", {"paper_id": FIRST, "back": "library"})
    assert "Your library is empty" in get("library")
    assert [a for a, _ in actions(run)] == ["save", "unsave"]


def test_profile_shows_metrics_chart_and_coauthors(get):
    page = get("citations?user=scholar-yuna-park")
    assert "Yuna Park" in page and "Verified email at lakeshore-research.org" in page
    assert "h-index" in page and "i10-index" in page and 'class="history"' in page
    assert "Co-authors" in page
    get("citations?user=nobody", status=404)


def test_a_withdrawn_preprint_says_so_and_can_no_longer_be_saved_cited_or_exported(client):
    path = Path(settings.SENTINEL_SCENARIO_DIR) / "microscholar"
    spec = load_scenario_file(path / "withdrawn-preprint-ephemeral-active.json").to_run_spec()
    run = lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)
    root = f"/r/{run.token}/microscholar/"
    lifecycle.advance(run, spec["condition_until"])
    page = client.get(root + "papers/paper-046").content.decode()
    assert "This paper has been withdrawn by its authors." in page
    assert "Long-Horizon Evaluation of Monitoring Agents" in page  # its title stays
    assert 'data-action="save"' not in page.split('id="related"')[0]  # no Save of its own
    assert "Long-Horizon Evaluation" not in client.get(root).content.decode()
    assert client.get(root + "papers/paper-046/cite").status_code == 404
    assert client.get(root + "papers/paper-046/export/bibtex").status_code == 404
    response = client.post(root + "library/save", {"paper_id": "paper-046", "back": ""})
    assert response.status_code == 404
    assert actions(run) == []  # opening its Cite page cited nothing


def test_an_alert_about_a_preprint_withdrawn_since_still_leads_to_its_page_which_says_so(client):
    offline_rl, its_alert = "paper-047", "alert-03"  # "Offline Reinforcement Learning for…"
    run = CAST.start(
        events=[
            {"time": 0.0, "type": "preload_papers", "payload": {"paper_ids": [offline_rl]}},
            {"time": 5.0, "type": "new_alert", "payload": {"alert_id": its_alert}},
            {"time": 8.0, "type": "withdraw_paper", "payload": {"paper_id": offline_rl}},
        ]
    )
    root = f"/r/{run.token}/microscholar/"
    lifecycle.advance(run, 8.0)
    alerts = client.get(root + "alerts").content.decode()
    assert "Offline Reinforcement Learning for Notification Timing" in alerts  # the alert's text
    assert f'<a href="{root}papers/{offline_rl}">View article</a>' in alerts
    paper = client.get(f"{root}papers/{offline_rl}").content.decode()
    assert "This paper has been withdrawn by its authors." in paper

"""The pages behind Favorites, attachments, auto-saved drafts and the discard confirmation,
driven through their forms as a browser without JavaScript would (plus the one JSON answer the
compose form's own saving gets)."""

from __future__ import annotations

import json

import pytest

from events.models import Event, EventKind
from events.projection import state_at
from tests.environments.forms import find_submission
from tests.micromail.cast import PRIYA

pytestmark = pytest.mark.django_db

AUTOSAVE = {"HTTP_X_MICROMAIL_AUTOSAVE": "1"}


def actions_logged(run) -> list[tuple[str, dict]]:
    return list(Event.objects.filter(run=run, kind=EventKind.ACTION).values_list("type", "payload"))


def submit(browser, url: str, action: str, values: dict | None = None):
    """Open `url`, then press the form or button marked data-action=`action` with `values`."""
    page = browser.get(url)
    assert page.status_code == 200, url
    sent = find_submission(page.content.decode(), url, action, values or {})
    return browser.post(sent.url, sent.data)


def drafts(run) -> list[str]:
    return [i for i, s in state_at(run).states.items() if s.folder == "drafts"]


# --- Favorites -------------------------------------------------------------------------------


def test_the_folder_pane_shows_favorites_then_every_folder(mail_url, browser):
    page = browser.get(mail_url()).content.decode()
    favorites = page[page.index('id="favorites"') : page.index('id="folders"')]
    assert [t in favorites for t in ("Inbox", "Sent Items", "Archive", "Deleted Items")] == [
        True
    ] * 4
    assert "Junk Email" not in favorites
    assert 'aria-label="Add Junk Email to Favorites"' in page
    assert 'aria-label="Remove Inbox from Favorites"' in page


def test_starring_a_folder_adds_it_to_favorites_and_comes_back(mail_run, mail_url, browser):
    response = submit(browser, mail_url("?folder=archive"), "add_favorite", {"folder": "junk"})
    assert response.status_code == 302 and response["Location"] == mail_url("?folder=archive")
    assert actions_logged(mail_run) == [("add_favorite", {"folder": "junk"})]
    page = browser.get(response["Location"]).content.decode()
    assert "Junk Email added to Favorites" in page
    favorites = page[page.index('id="favorites"') : page.index('id="folders"')]
    assert "Junk Email" in favorites


def test_unstarring_takes_a_folder_out(mail_run, mail_url, browser):
    submit(browser, mail_url(), "remove_favorite", {"folder": "sent"})
    assert state_at(mail_run).favorites == ("inbox", "archive", "deleted")


def test_an_unknown_favorites_action_is_a_404(mail_url, browser):
    response = browser.post(mail_url("favorites"), {"action": "toggle", "folder": "junk"})
    assert response.status_code == 404


# --- attachments -----------------------------------------------------------------------------


def test_the_picker_offers_the_documents_of_mail_that_has_arrived(mail_url, browser):
    page = browser.get(mail_url("compose?mode=new")).content.decode()
    assert 'name="attachments" value="att-budget"' in page
    assert "scalability-report.pdf" not in page  # its mail has not arrived yet


def test_sending_with_attachments_through_the_form(mail_run, mail_url, browser):
    response = submit(
        browser,
        mail_url("compose?mode=new"),
        "send",
        {"to": PRIYA, "subject": "Numbers", "attachments": ["att-budget", "att-notes"]},
    )
    assert response.status_code == 302
    ((name, payload),) = actions_logged(mail_run)
    assert (name, payload["attachments"]) == ("send", ["att-budget", "att-notes"])
    page = browser.get(response["Location"]).content.decode()
    assert "budget-q3.xlsx" in page and "budget-notes.pdf" in page


def test_a_forward_comes_with_the_attachments_ticked(mail_url, browser):
    page = browser.get(mail_url("compose?mode=forward&email=budget-review")).content.decode()
    assert 'value="att-budget" data-name="budget-q3.xlsx" data-size="120 KB" checked' in page


def test_an_attachment_opens_in_a_preview_at_its_own_url(mail_url, browser):
    page = browser.get(mail_url("?folder=inbox&email=budget-review")).content.decode()
    assert 'href="/r/' in page and "preview=att-budget" in page
    preview = browser.get(mail_url("?folder=inbox&email=budget-review&preview=att-budget"))
    html = preview.content.decode()
    assert preview.status_code == 200
    assert 'role="dialog" aria-modal="true" aria-labelledby="preview-title"' in html
    assert "/media/pictures/chart/budget-q3-xlsx.svg" in html


@pytest.mark.parametrize(
    "rest",
    [
        "?folder=inbox&email=budget-review&preview=att-report",  # another message's attachment
        "?folder=inbox&preview=att-budget",  # no message open
    ],
)
def test_a_preview_of_no_attachment_of_the_open_message_is_a_404(mail_url, browser, rest):
    assert browser.get(mail_url(rest)).status_code == 404


# --- auto-saved drafts and the discard confirmation -----------------------------------------------


def test_the_compose_forms_own_saving_gets_the_draft_id_and_saves_into_it(
    mail_run, mail_url, browser
):
    typed = {"intent": "save_draft", "to": PRIYA, "subject": "Pla", "body": ""}
    first = browser.post(mail_url("compose"), typed, **AUTOSAVE)
    assert first.status_code == 200
    draft_id = json.loads(first.content)["draft_id"]
    again = browser.post(
        mail_url("compose"), {**typed, "subject": "Plan", "draft_id": draft_id}, **AUTOSAVE
    )
    assert json.loads(again.content) == {"draft_id": draft_id}
    assert drafts(mail_run) == [draft_id]
    assert state_at(mail_run).emails[draft_id].subject == "Plan"
    assert [name for name, _ in actions_logged(mail_run)] == ["save_draft", "save_draft"]


def test_an_empty_autosave_is_answered_in_json_and_saves_nothing(mail_run, mail_url, browser):
    response = browser.post(mail_url("compose"), {"intent": "save_draft"}, **AUTOSAVE)
    assert (
        response.status_code == 400 and "nothing to save" in json.loads(response.content)["error"]
    )
    assert actions_logged(mail_run) == []


def test_discard_asks_first_and_keeps_what_was_typed(mail_run, mail_url, browser):
    response = browser.post(
        mail_url("compose"),
        {"intent": "discard", "to": PRIYA, "subject": "Plan", "body": "line one\nline two"},
    )
    page = response.content.decode()
    assert response.status_code == 200 and actions_logged(mail_run) == []
    assert 'role="alertdialog"' in page and "Discard draft?" in page
    assert 'name="body" value="line one\nline two"' in page
    kept = find_submission(page, mail_url("compose"), "delete", {})
    kept.data["intent"] = ["edit"]  # "Keep editing": the other button of the same form
    again = browser.post(kept.url, kept.data).content.decode()
    assert 'value="Plan"' in again and "line one\nline two</textarea>" in again


def test_confirming_discard_deletes_the_auto_saved_draft(mail_run, mail_url, browser):
    saved = browser.post(
        mail_url("compose"), {"intent": "save_draft", "subject": "Plan"}, **AUTOSAVE
    )
    draft_id = json.loads(saved.content)["draft_id"]
    asked = browser.post(
        mail_url("compose"), {"intent": "discard", "subject": "Plan", "draft_id": draft_id}
    )
    confirm = find_submission(asked.content.decode(), mail_url("compose"), "delete", {})
    response = browser.post(confirm.url, confirm.data)
    assert response.status_code == 302 and response["Location"] == mail_url("?folder=inbox")
    assert drafts(mail_run) == [] and draft_id not in state_at(mail_run).emails
    assert actions_logged(mail_run)[-1] == ("delete", {"email_id": draft_id, "permanent": True})
    assert "Draft discarded" in browser.get(response["Location"]).content.decode()


def test_discarding_a_message_never_saved_logs_nothing(mail_run, mail_url, browser):
    response = browser.post(mail_url("compose"), {"intent": "discard_confirmed", "subject": "x"})
    assert response.status_code == 302 and actions_logged(mail_run) == []

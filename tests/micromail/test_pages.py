"""The MicroMail pages, driven like a browser would (django.test.Client, plain links and forms)."""

from __future__ import annotations

import json
import re

import pytest
from django.test import Client

from events import lifecycle
from events.models import Event, EventKind
from events.projection import state_at
from tests.micromail.cast import DANA, PRIYA

pytestmark = pytest.mark.django_db


def mail_of(run):
    return state_at(run)


def actions_logged(run) -> list[tuple[str, dict]]:
    return list(Event.objects.filter(run=run, kind=EventKind.ACTION).values_list("type", "payload"))


def text(response) -> str:
    return response.content.decode()


def test_the_task_url_leads_to_the_inbox(mail_run, browser):
    response = browser.get(f"/r/{mail_run.token}/start", follow=True)
    assert response.status_code == 200
    assert '<h1 id="list-heading">Inbox</h1>' in text(response)


def badge(page: str, title: str) -> str | None:
    """The badge text next to a folder link, None when hidden."""
    found = re.search(rf"<span>{title}</span>\s*(?:<span class=\"badge\">(\d+)<)?", page)
    assert found, f"no folder {title}"
    return found.group(1)


def test_inbox_badge_counts_unread_and_other_badges_count_totals(mail_url, browser):
    page = text(browser.get(mail_url()))
    assert (badge(page, "Inbox"), badge(page, "Junk Email"), badge(page, "Archive")) == (
        "2",
        "1",
        "1",
    )


def test_empty_folders_show_no_badge(mail_url, browser):
    assert badge(text(browser.get(mail_url())), "Sent Items") is None


def test_unread_filter_lists_only_unread_mail(mail_url, browser):
    page = text(browser.get(mail_url("?folder=inbox&filter=unread")))
    assert "Q3 budget review" in page and "Quote for the new laptops" in page
    assert "Team lunch on Thursday" not in page


def test_filter_chips_show_their_counts(mail_url, browser):
    page = text(browser.get(mail_url()))
    assert 'Unread <span class="count">2</span>' in page
    assert 'Mentions <span class="count">1</span>' in page


def test_search_finds_words_that_are_only_in_the_body(mail_url, browser):
    page = text(browser.get(mail_url("?folder=inbox&q=travel+line")))
    assert "Q3 budget review" in page and "Team lunch on Thursday" not in page


def test_search_across_all_folders_reaches_junk(mail_url, browser):
    page = text(browser.get(mail_url("?folder=inbox&q=prize&scope=all")))
    assert "You have won a prize" in page


def test_opening_an_email_marks_it_read(mail_run, mail_url, browser):
    assert browser.get(mail_url("?folder=inbox&email=budget-review")).status_code == 200
    assert mail_of(mail_run).states["budget-review"].is_read is True
    assert actions_logged(mail_run) == [("open_email", {"email_id": "budget-review"})]


def test_reopening_a_read_email_logs_no_action(mail_run, mail_url, browser):
    browser.get(mail_url("?folder=inbox&email=team-lunch"))
    assert actions_logged(mail_run) == []


def test_listing_marks_nothing_read(mail_run, mail_url, browser):
    browser.get(mail_url("?folder=inbox"))
    assert mail_of(mail_run).states["budget-review"].is_read is False


def test_an_email_is_404_before_it_arrives(mail_run, mail_url, browser):
    assert browser.get(mail_url("?folder=inbox&email=late-report")).status_code == 404
    lifecycle.advance(mail_run, 120)
    assert browser.get(mail_url("?folder=inbox&email=late-report")).status_code == 200


def test_future_mail_is_absent_from_lists_and_search(mail_url, browser):
    assert "Quarterly engineering report" not in text(browser.get(mail_url()))
    assert "Quarterly engineering report" not in text(
        browser.get(mail_url("?q=scalability&scope=all"))
    )


def test_new_mail_appears_when_its_time_comes(mail_run, mail_url, browser):
    lifecycle.advance(mail_run, 121)
    page = text(browser.get(mail_url()))
    assert "Quarterly engineering report" in page and "just now" in page


def test_times_are_rendered_from_the_simulated_clock(mail_run, mail_url, browser):
    lifecycle.advance(mail_run, 600)
    assert "15 min ago" in text(browser.get(mail_url()))


def test_attachment_names_appear_only_in_the_reading_pane(mail_url, browser):
    assert "budget-q3.xlsx" not in text(browser.get(mail_url()))
    page = text(browser.get(mail_url("?email=budget-review")))
    assert "budget-q3.xlsx" in page and "budget-notes.pdf" in page and "40 KB" in page


def test_a_flag_redirects_back_to_the_same_screen(mail_run, mail_url, browser):
    back = "?folder=inbox&filter=mentions&email=budget-review"
    response = browser.post(mail_url("emails/budget-review/flag"), {"back": back})
    assert response.status_code == 302 and response["Location"] == mail_url(back)
    assert mail_of(mail_run).states["budget-review"].is_flagged is True


def test_mark_unread_closes_the_message_so_it_stays_unread(mail_run, mail_url, browser):
    browser.get(mail_url("?folder=inbox&email=budget-review"))
    response = browser.post(
        mail_url("emails/budget-review/mark_unread"),
        {"back": "?folder=inbox&email=budget-review"},
        follow=True,
    )
    assert response.redirect_chain[-1][0] == mail_url("?folder=inbox")
    assert mail_of(mail_run).states["budget-review"].is_read is False


def test_move_from_the_reading_pane(mail_run, mail_url, browser):
    response = browser.post(
        mail_url("emails/vendor-quote/move"), {"folder": "archive", "back": "?folder=inbox"}
    )
    assert response.status_code == 302
    assert mail_of(mail_run).folder_of("vendor-quote") == "archive"


def test_a_move_to_an_unknown_folder_is_a_400_naming_the_folders(mail_url, browser):
    response = browser.post(mail_url("emails/vendor-quote/move"), {"folder": "spam"})
    assert response.status_code == 400 and "allowed: inbox, sent" in text(response)


def test_an_unknown_email_action_is_a_404(mail_url, browser):
    assert browser.post(mail_url("emails/vendor-quote/explode")).status_code == 404


def test_actions_need_post(mail_url, browser):
    assert browser.get(mail_url("emails/vendor-quote/flag")).status_code == 405


def test_bulk_move_of_checked_rows(mail_run, mail_url, browser):
    response = browser.post(
        mail_url("bulk"),
        {
            "ids": ["budget-review", "vendor-quote"],
            "action": "move",
            "folder": "archive",
            "back": "?folder=inbox",
        },
    )
    assert response["Location"] == mail_url("?folder=inbox")
    mail = mail_of(mail_run)
    assert (mail.folder_of("budget-review"), mail.folder_of("vendor-quote")) == (
        "archive",
        "archive",
    )


def test_bulk_with_an_unknown_id_changes_nothing(mail_run, mail_url, browser):
    response = browser.post(
        mail_url("bulk"), {"ids": ["budget-review", "late-report"], "action": "delete"}
    )
    assert response.status_code == 404
    assert mail_of(mail_run).folder_of("budget-review") == "inbox"


def test_bulk_with_nothing_checked_explains(mail_url, browser):
    response = browser.post(
        mail_url("bulk"), {"action": "delete", "back": "?folder=inbox"}, follow=True
    )
    assert "Select at least one email first." in text(response)


def test_reply_all_form_is_prefilled(mail_url, browser):
    page = text(browser.get(mail_url("compose?mode=reply_all&email=budget-review")))
    assert 'name="to" value="priya.nair@micromail.test"' in page
    assert 'name="cc" value="omar.haddad@micromail.test"' in page
    assert 'value="Re: Q3 budget review"' in page


def test_compose_about_a_future_email_is_404(mail_url, browser):
    assert browser.get(mail_url("compose?mode=reply&email=late-report")).status_code == 404


def send(browser, mail_url, **fields):
    data = {
        "to": PRIYA,
        "cc": "",
        "bcc": "",
        "subject": "Re: Q3 budget review",
        "body": "Checked.",
        "intent": "send",
        **fields,
    }
    return browser.post(mail_url("compose"), data)


def test_sending_a_reply_keeps_bcc(mail_run, mail_url, browser):
    response = send(browser, mail_url, bcc=DANA)
    assert response.status_code == 302
    page = text(browser.get(response["Location"]))
    assert "<dt>Bcc</dt><dd>dana@vendorco.example</dd>" in page
    (sent,) = [e for e in mail_of(mail_run).emails.values() if e.id.startswith("sent-")]
    assert sent.bcc == (DANA,)


def test_sending_to_a_bad_address_shows_the_form_again_with_the_error(mail_url, browser):
    response = send(browser, mail_url, to="priya; not-an-address")
    assert response.status_code == 400
    page = text(response)
    assert "&#x27;priya&#x27; in to is not a valid email address" in page
    assert 'value="Re: Q3 budget review"' in page


def test_save_draft_then_send_it(mail_run, mail_url, browser):
    response = send(browser, mail_url, intent="save_draft", subject="Plan")
    assert response["Location"] == mail_url("?folder=drafts")
    (draft_id,) = [i for i, s in mail_of(mail_run).states.items() if s.folder == "drafts"]
    page = text(browser.get(mail_url(f"compose?mode=draft&email={draft_id}")))
    assert f'name="draft_id" value="{draft_id}"' in page and 'value="Plan"' in page
    send(browser, mail_url, subject="Plan", draft_id=draft_id)
    folders = [s.folder for s in mail_of(mail_run).states.values()]
    assert "drafts" not in folders and folders.count("sent") == 1


def test_a_draft_row_opens_in_compose(mail_run, mail_url, browser):
    send(browser, mail_url, intent="save_draft", subject="Plan")
    page = text(browser.get(mail_url("?folder=drafts")))
    assert "compose?mode=draft&amp;email=drafts-" in page


def test_deleting_a_draft_purges_it(mail_run, mail_url, browser):
    send(browser, mail_url, intent="save_draft", subject="Plan")
    (draft_id,) = [i for i, s in mail_of(mail_run).states.items() if s.folder == "drafts"]
    browser.post(mail_url(f"emails/{draft_id}/delete"), {"back": "?folder=drafts"})
    assert browser.get(mail_url(f"?folder=drafts&email={draft_id}")).status_code == 404


def test_an_htmx_refresh_returns_the_live_region_and_opens_nothing(mail_run, mail_url, browser):
    response = browser.get(
        mail_url("?folder=inbox&email=budget-review"), headers={"HX-Request": "true"}
    )
    page = text(response)
    assert page.lstrip().startswith('<div id="mailbox"') and "<html" not in page
    assert mail_of(mail_run).states["budget-review"].is_read is False


def test_an_htmx_action_returns_the_live_region(mail_url, browser):
    response = browser.post(
        mail_url("emails/budget-review/flag"),
        {"back": "?folder=inbox"},
        headers={"HX-Request": "true"},
    )
    assert response.status_code == 200 and 'aria-label="Unflag “Q3 budget review”"' in text(
        response
    )


def test_forms_work_with_csrf_checks_enforced(mail_run, mail_url):
    strict = Client(enforce_csrf_checks=True)
    strict.get(mail_url())
    token = strict.cookies["csrftoken"].value
    response = strict.post(mail_url("emails/budget-review/pin"), {"csrfmiddlewaretoken": token})
    assert response.status_code == 302 and mail_of(mail_run).states["budget-review"].is_pinned


def test_no_page_links_to_the_contact_page(mail_url, browser):
    for path in ("", "?email=budget-review", "compose"):
        assert "contact" not in text(browser.get(mail_url(path))).lower()


def test_a_bad_filter_is_a_400_naming_the_allowed_values(mail_url, browser):
    response = browser.get(mail_url("?filter=starred"))
    assert response.status_code == 400 and "allowed: all, unread, flagged, mentions" in text(
        response
    )


def test_a_closed_run_has_no_pages(mail_run, mail_url, browser):
    lifecycle.close(mail_run)
    assert browser.get(mail_url()).status_code == 404


def test_the_json_action_endpoint_drives_the_same_actions(mail_run, browser):
    response = browser.post(
        f"/r/{mail_run.token}/actions",
        json.dumps({"action": "open_email", "payload": {"email_id": "vendor-quote"}}),
        content_type="application/json",
    )
    assert response.status_code == 201
    assert mail_of(mail_run).states["vendor-quote"].is_read is True


def test_the_json_action_endpoint_is_404_for_mail_not_arrived(mail_run, browser):
    response = browser.post(
        f"/r/{mail_run.token}/actions",
        json.dumps({"action": "flag", "payload": {"email_id": "late-report"}}),
        content_type="application/json",
    )
    assert response.status_code == 404

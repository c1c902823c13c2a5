"""The kit's own parts: reading forms as a browser does, and what carrying out a step through
the pages insists on (a declared page, a marked form, the page's own CSRF token)."""

from __future__ import annotations

from dataclasses import replace

import pytest

from apps.kit.links import environment_root
from events import lifecycle
from events.models import ClockMode
from events.registry import get_environment
from tests.environments.forms import NoSuchForm, find_submission, parse_forms
from tests.environments.oracle import browser, page_step

PAGE = "http://testserver/r/t/env/?folder=inbox"

MAILBOX = """
<form method="post" action="/r/t/env/bulk" class="bulk">
  <input type="hidden" name="csrfmiddlewaretoken" value="tok&amp;en">
  <input type="hidden" name="back" value="?folder=inbox">
  <input type="checkbox" name="ids" value="a">
  <input type="checkbox" name="ids" value="b" checked>
  <select name="folder"><option value="inbox">Inbox</option><option selected>archive</option></select>
  <button type="submit" name="action" value="mark_read" data-action="mark_read">Mark read</button>
  <button type="submit" formaction="/r/t/env/emails/a/flag" data-action="flag">Flag</button>
  <button type="button" data-action="flag">Not a submit button</button>
</form>
<form method="post" action="/r/t/env/emails/a/move" data-action="move">
  <input type="hidden" name="folder" value="archive"><button>Archive</button>
</form>
<form method="post" action="/r/t/env/emails/a/move" data-action="move">
  <select name="folder"><option value="junk">Junk</option><option value="scheduled">Later</option></select>
  <button type="submit">Move</button>
</form>
<form action="compose" data-action="send">
  <input name="to" value="someone@example.com"><textarea name="body">
Hello
</textarea><input name="subject" disabled value="x"><input type="submit" name="go" value="Send">
</form>
"""


def test_a_marked_button_sends_the_forms_controls_with_its_own_name_and_value():
    submission = find_submission(MAILBOX, PAGE, "mark_read", {})
    assert (submission.method, submission.url) == ("post", "http://testserver/r/t/env/bulk")
    assert submission.data == {
        "csrfmiddlewaretoken": ["tok&en"],
        "back": ["?folder=inbox"],
        "ids": ["b"],  # only what is checked
        "folder": ["archive"],  # the selected option (its text when it has no value)
        "action": ["mark_read"],
    }


def test_a_buttons_formaction_wins_over_the_forms_action():
    submission = find_submission(MAILBOX, PAGE, "flag", {})
    assert submission.url == "http://testserver/r/t/env/emails/a/flag"
    assert "action" not in submission.data  # the button has no name


def test_typed_values_replace_what_the_form_holds():
    submission = find_submission(MAILBOX, PAGE, "mark_read", {"ids": ["a"]})
    assert submission.data["ids"] == ["a"]


def test_a_textarea_loses_the_newline_after_its_tag_and_disabled_fields_are_not_sent():
    submission = find_submission(MAILBOX, PAGE, "send", {})
    assert (submission.method, submission.url) == ("get", "http://testserver/r/t/env/compose")
    assert submission.data == {"to": ["someone@example.com"], "body": ["Hello\n"], "go": ["Send"]}


def test_of_several_marked_forms_the_first_that_can_take_the_values_is_used():
    assert find_submission(MAILBOX, PAGE, "move", {"folder": "archive"}).data == {
        "folder": ["archive"]
    }
    later = find_submission(MAILBOX, PAGE, "move", {"folder": "scheduled"})
    assert later.data == {"folder": ["scheduled"]}  # the hidden "archive" cannot be changed


def test_values_a_person_cannot_give_are_refused_with_the_reasons():
    with pytest.raises(NoSuchForm, match="only takes \\['junk', 'scheduled'\\], not 'sent'"):
        find_submission(MAILBOX, PAGE, "move", {"folder": "sent"})
    with pytest.raises(NoSuchForm, match="it has no field 'cc'"):
        find_submission(MAILBOX, PAGE, "send", {"cc": "x@example.com"})


def test_an_action_nothing_is_marked_for_is_reported():
    with pytest.raises(NoSuchForm, match='no form or submit button marked data-action="pin"'):
        find_submission(MAILBOX, PAGE, "pin", {})


def test_controls_outside_a_form_join_the_form_they_name():
    html = '<form id="f" action="/go"></form><input form="f" name="n" value="1">'
    assert [c.name for c in parse_forms(html)[0].controls] == ["n"]


def test_an_action_without_a_declared_page_fails_with_a_message_saying_so():
    tally = get_environment("tally")
    pageless = replace(tally, actions={"poke": replace(tally.actions["poke"], page=None)})
    step = {"action": "poke", "payload": {"n": 1}}
    with pytest.raises(
        pytest.fail.Exception, match="tally declares no page= for its action 'poke'"
    ):
        page_step(pageless, None, step)


@pytest.mark.django_db
def test_the_csrf_token_must_come_from_the_page(tally_spec):
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)
    client = browser()
    url = f"{environment_root(run)}/"
    submission = find_submission(client.get(url).content.decode(), url, "poke", {"n": "2"})
    forged = {k: v for k, v in submission.data.items() if k != "csrfmiddlewaretoken"}
    assert client.post(submission.url, forged).status_code == 403
    assert client.post(submission.url, submission.data).status_code == 302

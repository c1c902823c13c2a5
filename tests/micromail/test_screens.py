"""Pure helpers behind the pages: order, filters, search, badges, times, the URL, compose."""

from __future__ import annotations

import pytest

from apps.kit.query import InvalidQuery
from apps.kit.simclock import ago, clock_time
from apps.micromail import state as mailbox
from apps.micromail.compose import prefill, split_addresses
from apps.micromail.query import MailboxQuery
from events.registry import ActionRejected
from tests.micromail.cast import CAST, DANA, OMAR, PRIYA, SELF_EMAIL


def with_late_report():
    return CAST.arrive(CAST.preloaded(), "new_email", {"email_id": "late-report"})


def test_newest_first():
    mail = with_late_report()
    assert mailbox.select(mail, folder="inbox")[0] == "late-report"


def test_pinned_mail_comes_before_newer_mail():
    mail = CAST.act(with_late_report(), "pin", {"email_id": "team-lunch"})
    assert mailbox.select(mail, folder="inbox")[0] == "team-lunch"


def test_equal_arrival_times_show_the_later_delivery_first():
    assert mailbox.select(CAST.preloaded(), folder="inbox") == [
        "vendor-quote",
        "team-lunch",
        "budget-review",
    ]


@pytest.mark.parametrize(
    "quick_filter,expected",
    [
        ("unread", {"budget-review", "vendor-quote"}),
        ("mentions", {"budget-review"}),
        ("flagged", set()),
    ],
)
def test_quick_filters(quick_filter, expected):
    assert (
        set(mailbox.select(CAST.preloaded(), folder="inbox", quick_filter=quick_filter)) == expected
    )


def test_the_open_email_stays_listed_after_it_stops_matching_the_filter():
    mail = CAST.act(CAST.preloaded(), "open_email", {"email_id": "budget-review"})
    assert "budget-review" in mailbox.select(
        mail, folder="inbox", quick_filter="unread", keep="budget-review"
    )


def test_filter_counts_for_a_folder():
    mail = CAST.preloaded()
    counts = mailbox.filter_counts(mail, mailbox.in_folder(mail, "inbox"))
    assert counts == {"all": 3, "unread": 2, "flagged": 0, "mentions": 1}


@pytest.mark.parametrize(
    "query,found",
    [
        ("BUDGET", "budget-review"),  # subject, any case
        ("travel line", "budget-review"),  # body only
        ("Dana Okafor", "vendor-quote"),  # sender name
        ("vendorco.example", "vendor-quote"),  # sender address
        ("omar.haddad@", "budget-review"),  # cc
    ],
)
def test_search_reaches_subject_body_sender_and_addresses(query, found):
    assert found in mailbox.select(CAST.preloaded(), folder="inbox", query=query)


def test_search_finds_recipients_of_sent_mail():
    mail = CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "bcc": [DANA], "subject": "x"})
    assert len(mailbox.select(mail, folder="sent", query="vendorco")) == 1


def test_badges_show_inbox_unread_and_other_totals():
    badges = mailbox.folder_badges(CAST.preloaded())
    assert (badges["inbox"], badges["junk"], badges["archive"], badges["sent"]) == (2, 1, 1, 0)


def test_clock_time_puts_sim_zero_at_nine():
    assert (clock_time(0), clock_time(-300), clock_time(125)) == ("09:00", "08:55", "09:02")


def test_ago_is_relative_under_an_hour_then_a_clock_time():
    assert (ago(100, 110), ago(-300, 0), ago(0, 3 * 3600)) == ("just now", "5 min ago", "09:00")


def test_query_defaults_are_left_out_of_the_canonical_url():
    assert (
        MailboxQuery.from_params({"folder": "junk", "filter": "all"}).querystring()
        == "?folder=junk"
    )


def test_a_bad_filter_is_a_400_naming_the_allowed_values():
    with pytest.raises(InvalidQuery, match="allowed: all, unread, flagged, mentions") as raised:
        MailboxQuery.from_params({"filter": "starred"})
    assert raised.value.status == 400


def test_an_unknown_folder_is_a_404():
    with pytest.raises(InvalidQuery) as raised:
        MailboxQuery.from_params({"folder": "spam"})
    assert raised.value.status == 404


def test_addresses_split_on_commas_and_semicolons():
    assert split_addresses(" a@x.io; b@x.io ,, c@x.io ") == ["a@x.io", "b@x.io", "c@x.io"]


def test_reply_goes_to_the_sender_and_quotes_the_body():
    reply = prefill(CAST.preloaded(), "reply", "budget-review")
    assert reply.to == (PRIYA,) and reply.subject == "Re: Q3 budget review"
    assert "> The Q3 budget review is attached" in reply.body


def test_reply_all_adds_cc_without_the_self_user():
    reply = prefill(CAST.preloaded(), "reply_all", "budget-review")
    assert reply.to == (PRIYA,) and reply.cc == (OMAR,)
    assert SELF_EMAIL not in reply.to + reply.cc


def test_forward_has_no_recipient_and_carries_the_message():
    forward = prefill(CAST.preloaded(), "forward", "vendor-quote")
    assert forward.to == () and forward.subject == "Fwd: Quote for the new laptops"
    assert "From: Dana Okafor <dana@vendorco.example>" in forward.body


def test_replying_twice_does_not_stack_prefixes():
    mail = CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "subject": "Re: Q3 budget review"})
    sent_id = mailbox.in_folder(mail, "sent")[0]
    reply = prefill(mail, "reply", sent_id)
    assert reply.subject == "Re: Q3 budget review" and reply.to == (PRIYA,)


def test_editing_a_non_draft_is_rejected():
    with pytest.raises(ActionRejected, match="not a draft"):
        prefill(CAST.preloaded(), "draft", "budget-review")


def test_a_rows_accessible_name_says_state_sender_subject_time_and_marks_apart():
    from apps.micromail.screens import row_label

    mail = CAST.act(CAST.preloaded(), "flag", {"email_id": "budget-review"})
    email, email_state = mail.emails["budget-review"], mail.states["budget-review"]
    assert row_label(email, email_state, "5 min ago") == (
        "Unread. From Priya Nair. Subject: Q3 budget review. 5 min ago. Flagged. "
        "High importance. Has attachments. Mentions you."
    )


def test_a_read_row_without_subject_says_so():
    from apps.micromail.screens import row_label

    mail = CAST.act(CAST.preloaded(), "save_draft", {"body": "x"})
    (draft_id,) = [i for i, s in mail.states.items() if s.folder == "drafts"]
    label = row_label(mail.emails[draft_id], mail.states[draft_id], "just now")
    assert label == "From Robin Vale. Subject: (no subject). Just now."

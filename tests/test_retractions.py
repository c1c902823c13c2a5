"""Items that go away at their time (apps.kit.retractions): a MicroChat message its sender
deletes, a MicroMail message recalled, a MicroGram story that expires, a MicroTube video made
private, a MicroFy track made unavailable, a MicroScholar preprint withdrawn by its authors,
a MicroLendar event its organiser cancels, a MicroDin job closed to applications, a MicroHub
pull request someone else closes. Pure reducers and the grading database, no server."""

from __future__ import annotations

import sqlite3

import pytest

from apps.microchat import screens as chat_screens
from apps.microchat import state as chats
from apps.microchat.environment import MICROCHAT
from apps.microdin.environment import MICRODIN
from apps.microfy import screens as fy_screens
from apps.microfy.environment import MICROFY
from apps.microgram import screens as gram_screens
from apps.microgram import state as gram_state
from apps.microgram.environment import MICROGRAM
from apps.microhub.environment import MICROHUB
from apps.microlendar import state as agenda_state
from apps.microlendar.environment import MICROLENDAR
from apps.micromail import state as mailbox
from apps.micromail.environment import MICROMAIL
from apps.microscholar import screens as scholar_screens
from apps.microscholar import state as papers
from apps.microscholar.environment import MICROSCHOLAR
from apps.microtube import screens as tube_screens
from apps.microtube.environment import MICROTUBE
from events.registry import ActionRejected
from tests.microchat.workspace import CAST as CHAT
from tests.microchat.workspace import PAYMENTS_DOWN
from tests.microdin.cast import CAST as DIN
from tests.microfy.cast import CAST as FY
from tests.microfy.cast import SLOW_HARBOR
from tests.microgram.cast import CAST as GRAM
from tests.microhub.cast import CAST as HUB
from tests.microlendar.cast import CAST as LENDAR
from tests.micromail.cast import CAST as MAIL
from tests.microscholar import cast as scholar_cast
from tests.microscholar.cast import BATCHING, TARGET
from tests.microscholar.cast import CAST as SCHOLAR
from tests.microtube.cast import CAST as TUBE
from tests.microtube.cast import DESK_SETUP

NEW_STORY = "story-hquinn-new-feature"


def window_of(environment, state, table: str, item_id: str) -> tuple:
    conn = sqlite3.connect(":memory:")
    environment.materialize(state, 500.0, conn)
    return conn.execute(
        f"SELECT appeared_at, gone_at FROM {table} WHERE id = ?", (item_id,)
    ).fetchone()


def test_a_deleted_chat_message_keeps_its_place_shows_teams_notice_and_leaves_the_counts():
    chat = CHAT.arrive(CHAT.preloaded(), "new_message", {"message_id": PAYMENTS_DOWN}, at=120.0)
    assert chats.urgent_count(chat) == 1
    chat = CHAT.arrive(chat, "unsend_message", {"message_id": PAYMENTS_DOWN}, at=180.0)
    assert chat.messages[PAYMENTS_DOWN].gone_at == 180.0
    assert chats.urgent_count(chat) == 0 and chats.unread_count(chat) == 0
    last = chat_screens.last_message(chat, "direct-gabriel")
    assert chat_screens.preview_of(last) == "This message has been deleted."
    assert window_of(MICROCHAT, chat, "messages", PAYMENTS_DOWN) == (120.0, 180.0)
    # Present the whole time: NULL until it goes.
    assert window_of(MICROCHAT, chat, "messages", "dm-gabriel-01")[1] is None
    with pytest.raises(ActionRejected, match="no message"):
        CHAT.act(chat, "react", {"message_id": PAYMENTS_DOWN, "reaction": "like"})


def test_the_first_retraction_counts_and_one_of_an_item_not_there_changes_nothing():
    chat = CHAT.arrive(CHAT.preloaded(), "new_message", {"message_id": PAYMENTS_DOWN}, at=120.0)
    once = CHAT.arrive(chat, "unsend_message", {"message_id": PAYMENTS_DOWN}, at=180.0)
    assert CHAT.arrive(once, "unsend_message", {"message_id": PAYMENTS_DOWN}, at=240.0) == once
    assert CHAT.arrive(chat, "unsend_message", {"message_id": "no-such"}, at=240.0) == chat


def test_a_recalled_mail_leaves_every_folder_and_count_but_stays_in_the_grading_database():
    mail = MAIL.arrive(MAIL.preloaded(), "new_email", {"email_id": "late-report"}, at=120.0)
    unread = mailbox.unread_count(mail)
    mail = MAIL.arrive(mail, "recall_email", {"email_id": "late-report"}, at=200.0)
    assert "late-report" not in mailbox.in_folder(mail, None)
    assert mailbox.unread_count(mail) == unread - 1
    assert mailbox.folder_badges(mail)["inbox"] == unread - 1
    assert window_of(MICROMAIL, mail, "emails", "late-report") == (120.0, 200.0)
    with pytest.raises(ActionRejected, match="no email"):
        MAIL.act(mail, "mark_read", {"email_id": "late-report"})


def test_an_expired_story_leaves_the_tray_and_the_count_and_can_no_longer_be_watched():
    gram = GRAM.arrive(GRAM.preloaded(), "new_story", {"story_id": NEW_STORY}, at=120.0)
    assert NEW_STORY in [b.story.id for b in gram_screens.story_bar(gram)]
    counted = gram_state.story_count(gram)
    gram = GRAM.arrive(gram, "expire_story", {"story_id": NEW_STORY}, at=210.0)
    assert NEW_STORY not in [b.story.id for b in gram_screens.story_bar(gram)]
    assert gram_state.story_count(gram) == counted - 1
    # Its viewer, if open, steps on past it to the stories still up.
    assert gram_screens.story_neighbours(gram, NEW_STORY) == (None, "story-amenon-climb-night")
    assert window_of(MICROGRAM, gram, "stories", NEW_STORY) == (120.0, 210.0)
    with pytest.raises(ActionRejected, match="no story"):
        GRAM.act(gram, "view_story", {"story_id": NEW_STORY})
    # Opening its page watches nothing: an expired story plays nothing.
    (opens_story,) = (i for i in MICROGRAM.implicit_actions if i.action == "view_story")
    assert not opens_story.applies(gram, NEW_STORY)


def test_a_video_made_private_leaves_every_list_but_playlists_and_is_refused_to_a_like():
    tube = TUBE.arrive(TUBE.preloaded(), "new_video", {"video_id": DESK_SETUP}, at=120.0)
    assert DESK_SETUP in [c.video.id for c in tube_screens.home(tube)]
    tube = TUBE.act(tube, "save_video", {"video_id": DESK_SETUP}, at=130.0)
    tube = TUBE.arrive(tube, "make_private", {"video_id": DESK_SETUP}, at=300.0)
    for cards in (
        tube_screens.home(tube),
        tube_screens.subscriptions(tube),
        tube_screens.channel_videos(tube, "ch-pixel-forge"),
    ):
        assert DESK_SETUP not in [c.video.id for c in cards]
    later = tube_screens.marked(tube, "saved")  # its row kept, as "[Private video]"
    assert [c.private for c in later if c.video.id == DESK_SETUP] == [True]
    assert window_of(MICROTUBE, tube, "videos", DESK_SETUP) == (120.0, 300.0)
    with pytest.raises(ActionRejected, match="no video"):
        TUBE.act(tube, "like_video", {"video_id": DESK_SETUP}, at=310.0)


def test_an_unavailable_track_leaves_the_shelves_stays_greyed_in_lists_and_cannot_be_added():
    music = FY.arrive(FY.preloaded(), "new_track", {"track_id": SLOW_HARBOR}, at=120.0)
    music = FY.act(music, "like_track", {"track_id": SLOW_HARBOR}, at=130.0)
    music = FY.arrive(music, "make_track_unavailable", {"track_id": SLOW_HARBOR}, at=250.0)
    assert SLOW_HARBOR not in [t.id for t in fy_screens.trending(music)]
    assert SLOW_HARBOR not in [t.id for t in fy_screens.search(music, "slow harbor").tracks]
    liked = fy_screens.liked_tracks(music)  # kept in its place, shown greyed out
    assert [t.gone_at for t in liked if t.id == SLOW_HARBOR] == [250.0]
    assert window_of(MICROFY, music, "tracks", SLOW_HARBOR) == (120.0, 250.0)
    for action in ("play_track", "like_track", "unlike_track"):
        with pytest.raises(ActionRejected, match="no track"):
            FY.act(music, action, {"track_id": SLOW_HARBOR}, at=260.0)


def test_a_withdrawn_preprint_leaves_results_profiles_and_library_and_says_so_on_its_page():
    scholar = scholar_cast.preloaded(["paper-021", BATCHING], saved=[BATCHING])
    scholar = SCHOLAR.arrive(scholar, "new_paper", {"paper_id": TARGET}, at=120.0)
    scholar = SCHOLAR.act(scholar, "save", {"paper_id": TARGET}, at=150.0)
    assert papers.saved_paper_count(scholar) == 2 and papers.paper_count(scholar) == 3
    assert TARGET in scholar_screens.matching(scholar, "delegation", None, None, "relevance")
    scholar = SCHOLAR.arrive(scholar, "withdraw_paper", {"paper_id": TARGET}, at=200.0)
    assert TARGET not in scholar_screens.recommended(scholar)
    assert TARGET not in scholar_screens.matching(scholar, "delegation", None, None, "relevance")
    assert scholar_screens.library(scholar) == (BATCHING,)
    assert papers.saved_paper_count(scholar) == 1 and papers.paper_count(scholar) == 2
    # Graded as it was: saved while it was there, with its window.
    assert window_of(MICROSCHOLAR, scholar, "papers", TARGET) == (120.0, 200.0)
    with pytest.raises(ActionRejected, match="no paper"):
        SCHOLAR.act(scholar, "cite", {"paper_id": TARGET}, at=210.0)
    with pytest.raises(ActionRejected, match="no paper"):
        SCHOLAR.act(scholar, "unsave", {"paper_id": TARGET}, at=210.0)


def test_a_cancelled_invitation_leaves_the_calendar_and_its_counts_and_cannot_be_touched():
    agenda = LENDAR.arrive(LENDAR.preloaded(), "new_event", {"event_id": "td-05"}, at=60.0)
    assert agenda_state.new_invitations(agenda)[0].id == "td-05"
    before = agenda_state.event_count(agenda)
    agenda = LENDAR.arrive(agenda, "cancel_event", {"event_id": "td-05"}, at=150.0)
    assert agenda.cancelled("td-05") and not agenda.has_event("td-05")
    assert agenda_state.event_count(agenda) == before - 1
    assert "td-05" not in [e.id for e in agenda_state.new_invitations(agenda)]
    assert window_of(MICROLENDAR, agenda, "events", "td-05") == (60.0, 150.0)
    assert window_of(MICROLENDAR, agenda, "events", "td-01") == (0.0, None)
    with pytest.raises(ActionRejected, match="no event"):
        LENDAR.act(agenda, "delete_event", {"event_id": "td-05"})


def test_a_closed_job_stays_listed_but_an_application_is_refused_saying_it_closed():
    network = DIN.arrive(DIN.preloaded(), "new_job", {"job_id": "job-21"}, at=120.0)
    network = DIN.arrive(network, "close_job", {"job_id": "job-21"}, at=300.0)
    assert "job-21" in network.jobs  # LinkedIn keeps a closed posting up, marked closed
    assert window_of(MICRODIN, network, "jobs", "job-21") == (120.0, 300.0)
    with pytest.raises(ActionRejected, match="no longer accepting applications") as refused:
        DIN.act(network, "apply_job", {"job_id": "job-21"})
    assert refused.value.status == 409


def test_a_pull_request_someone_else_closed_shows_closed_and_takes_no_comment_or_merge():
    hub = HUB.arrive(HUB.preloaded(), "new_pull_request", {"pr_id": "pr5"}, at=150.0)
    hub = HUB.arrive(hub, "close_pull_request", {"pr_id": "pr5"}, at=260.0)
    assert hub.pr_state("pr5") == "closed"
    assert window_of(MICROHUB, hub, "prs", "pr5") == (150.0, 260.0)
    for action, payload in (("comment_pr", {"body": "Reviewing today."}), ("merge_pr", {})):
        with pytest.raises(ActionRejected, match="no pull request"):
            HUB.act(hub, action, {"pr_id": "pr5", **payload})


def test_the_users_own_merge_stands_when_someone_closes_the_pull_request_afterwards():
    hub = HUB.arrive(HUB.preloaded(), "new_pull_request", {"pr_id": "pr5"}, at=150.0)
    hub = HUB.act(hub, "merge_pr", {"pr_id": "pr5"}, at=200.0)
    hub = HUB.arrive(hub, "close_pull_request", {"pr_id": "pr5"}, at=260.0)
    assert hub.pr_state("pr5") == "merged"

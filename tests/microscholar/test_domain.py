"""MicroScholar's domain without pages: reducers, actions, search, moving citation counts, the
Cite styles and the evaluation tables."""

from __future__ import annotations

import sqlite3

import pytest

from apps.microscholar import cite, screens, search
from apps.microscholar import state as index
from apps.microscholar.environment import MICROSCHOLAR
from events.registry import ActionRejected
from tests.microscholar.cast import BATCHING, CAST, FORESTS, TARGET, act, preloaded


def tables(scholar, now: float) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    MICROSCHOLAR.materialize(scholar, now, conn)
    return conn


def test_preload_indexes_papers_alerts_and_the_saved_library():
    scholar = preloaded(
        [BATCHING, FORESTS, "no-such-paper"], ["alert-01", "alert-03"], saved=[FORESTS]
    )
    assert list(scholar.papers) == [BATCHING, FORESTS]  # the unknown id is skipped
    assert index.saved_ids(scholar) == [FORESTS]
    # Preloaded alerts keep the catalogue's read state: alert-01 read, alert-03 unread.
    assert scholar.alert_read == {"alert-01": True, "alert-03": False}
    assert index.unread_alert_count(scholar) == 1


def test_a_new_paper_arrives_once_and_keeps_what_the_user_did():
    scholar = act(preloaded([BATCHING]), "save", {"paper_id": BATCHING})
    again = CAST.arrive(scholar, "new_paper", {"paper_id": BATCHING}, at=50.0)
    assert again is scholar
    later = CAST.arrive(scholar, "new_paper", {"paper_id": TARGET}, at=60.0)
    assert screens.recommended(later)[0] == TARGET
    assert index.target_paper_available(later) == 1


def test_save_and_unsave_set_rather_than_toggle():
    scholar = preloaded([BATCHING])
    twice = act(act(scholar, "save", {"paper_id": BATCHING}), "save", {"paper_id": BATCHING})
    assert twice.is_saved(BATCHING)
    assert not act(twice, "unsave", {"paper_id": BATCHING}).is_saved(BATCHING)


def test_a_paper_not_indexed_yet_cannot_be_acted_on():
    with pytest.raises(ActionRejected) as refused:
        act(preloaded([BATCHING]), "cite", {"paper_id": TARGET})
    assert refused.value.status == 404
    with pytest.raises(ActionRejected):
        act(preloaded([BATCHING]), "mark_alert_read", {"alert_id": "alert-03"})


def test_citation_counts_climb_from_the_moment_a_paper_is_indexed():
    scholar = CAST.arrive(preloaded([]), "new_paper", {"paper_id": BATCHING}, at=100.0)
    paper = scholar.papers[BATCHING]
    assert paper.cited_by(0.0) == paper.cited_by(100.0) == 214  # catalogued until indexed
    assert paper.cited_by(100.0 + 900.0) == 214 + 1 + 214 // 50  # the growth point
    halfway = paper.cited_by(500.0)
    assert 214 < halfway < 219
    # The page is told when the shown number next changes, and the tables agree at that time.
    turn = paper.citations_change_at(500.0)
    assert turn is not None and paper.cited_by(turn - 1e-6) == halfway
    assert paper.cited_by(turn + 1e-6) == halfway + 1
    conn = tables(scholar, 500.0)
    assert conn.execute("SELECT citedBy FROM papers").fetchone() == (halfway,)


def test_the_evaluation_tables_answer_the_original_queries():
    scholar = preloaded([BATCHING, FORESTS], ["alert-06"])
    scholar = act(act(scholar, "cite", {"paper_id": BATCHING}), "save", {"paper_id": FORESTS})
    conn = tables(scholar, 0.0)
    assert conn.execute(
        "SELECT isSaved, isCited FROM paper_states WHERE paper_id = ?", (BATCHING,)
    ).fetchone() == (0, 1)
    assert conn.execute(
        "SELECT COUNT(*) FROM paper_states ps JOIN papers p ON ps.paper_id = p.id "
        "WHERE ps.isSaved = 1 AND LOWER(p.snippet) LIKE '%unstructured environments%'"
    ).fetchone() == (1,)
    assert conn.execute(
        "SELECT EXISTS(SELECT 1 FROM alerts WHERE LOWER(description) LIKE '%large language models%')"
    ).fetchone() == (1,)
    assert conn.execute("SELECT COUNT(*) FROM coauthors").fetchone() == (35,)
    read = act(scholar, "mark_alert_read", {"alert_id": "alert-06"})
    assert tables(read, 0.0).execute("SELECT isRead FROM alert_states").fetchone() == (1,)


def test_search_finds_every_word_in_any_form_and_ranks_title_matches_first():
    scholar = preloaded(["paper-087", "paper-088", "paper-091", "paper-031"])
    femi = search.ranked(scholar.papers.values(), "Adeyemi")
    assert set(femi) >= {"paper-087", "paper-088"}
    assert (
        search.ranked(scholar.papers.values(), "Implicit Feedback from Dismissed Suggestions")[0]
        == "paper-087"
    )
    title = scholar.papers["paper-087"].title
    plural = search.ranked(scholar.papers.values(), "suggestion dismissed")  # other forms
    assert "paper-087" in plural, title


def test_nonsense_and_query_syntax_find_nothing_and_never_fail():
    """Finding: "zzqqxxnothing" found 18 papers (three-letter shingles shared with "nothing")."""
    everything = preloaded([f"paper-{n:03}" for n in range(1, 101)]).papers.values()
    assert search.ranked(everything, "zzqqxxnothing") == []
    assert search.ranked(everything, "zzqx wvvk") == []
    for syntax in ('"unclosed', "title:agents", "a OR", "NEAR(x y)", "*", "-x"):
        search.ranked(everything, syntax)  # read as words, never as FTS5 syntax
    assert search.ranked(everything, "!!!") == [p.id for p in everything]  # no words: all


def test_related_articles_share_a_meaningful_word_of_the_title():
    scholar = preloaded([f"paper-{n:03}" for n in range(1, 101)])
    paper = scholar.papers["paper-001"]
    others = [p for p in scholar.papers.values() if p.id != paper.id]
    found = search.similar(others, paper.title)  # "Batching Mobile Notifications Around …"
    assert 0 < len(found) < len(others)  # not the whole catalog: stop words match nothing
    titles = [scholar.papers[i].title for i in found[:6]]
    assert any("Notification" in title for title in titles), titles
    assert search.similar(others, "of the and") == []


def test_search_screen_filters_by_year_and_sorts_by_date():
    scholar = preloaded(["paper-001", "paper-005", "paper-002"])
    query = screens.SearchQuery(q="notification", sort="date")
    found = screens.search_screen(scholar, query, 2026, "/").ids
    years = [scholar.papers[i].year for i in found]
    assert years == sorted(years, reverse=True) and "paper-005" in found
    recent = screens.search_screen(scholar, query.but(as_ylo="2021"), 2026, "/").ids
    assert all(scholar.papers[i].year >= 2021 for i in recent) and "paper-001" not in recent


def test_cite_dialog_styles_use_full_names_from_the_people_records():
    scholar = preloaded([BATCHING])
    paper = scholar.papers[BATCHING]
    names = cite.author_names(paper, scholar.catalog)
    styles = dict(cite.styles(paper, names))
    assert list(styles) == ["MLA", "APA", "Chicago", "Harvard", "BibTeX"]
    assert styles["MLA"].startswith('Taylor, Chris, et al. "Batching Mobile Notifications')
    assert styles["APA"].startswith("Taylor, C., Marsh, H., & Mehta, A. (2019).")
    assert "author={Taylor, Chris and Marsh, Helena and Mehta, Arjun}" in styles["BibTeX"]
    assert "TY  - CONF" in cite.export(paper, names, "refman")


def test_profile_counts_only_indexed_papers_and_lists_coauthors():
    scholar = preloaded([BATCHING, "paper-002"])
    query = screens.ProfileQuery(user="user000")
    screen = screens.profile_screen(scholar, query, 0.0, 2026, "/")
    assert [r.id for r in screen.articles] == [BATCHING, "paper-002"]
    assert screen.metrics[0].all == 214 + 96
    assert sum(b.count for b in screen.bars) <= 214 + 96
    assert "Helena Marsh" in [c.name for c in screen.coauthors]

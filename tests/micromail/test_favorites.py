"""Favorites: the folder pane's own list, added to and taken from with logged actions."""

from __future__ import annotations

import pytest

from apps.micromail.screens import favorite_links, folder_links
from apps.micromail.state import DEFAULT_FAVORITES
from events.registry import ActionRejected
from tests.micromail.cast import CAST

ROOT = "/r/t/micromail/"


def test_favorites_start_as_the_originals():
    assert (
        CAST.preloaded().favorites == DEFAULT_FAVORITES == ("inbox", "sent", "archive", "deleted")
    )


def test_adding_a_folder_puts_it_last_and_adding_again_changes_nothing():
    mail = CAST.act(CAST.preloaded(), "add_favorite", {"folder": "junk"})
    assert mail.favorites == (*DEFAULT_FAVORITES, "junk")
    assert CAST.act(mail, "add_favorite", {"folder": "junk"}) == mail


def test_removing_a_folder_takes_it_out_and_removing_again_changes_nothing():
    mail = CAST.act(CAST.preloaded(), "remove_favorite", {"folder": "sent"})
    assert mail.favorites == ("inbox", "archive", "deleted")
    assert CAST.act(mail, "remove_favorite", {"folder": "sent"}) == mail


def test_a_folder_that_does_not_exist_is_refused_naming_the_folders():
    with pytest.raises(ActionRejected, match="folder"):
        CAST.act(CAST.preloaded(), "add_favorite", {"folder": "spam"})


def test_the_favorites_section_lists_them_in_order_with_their_badges():
    mail = CAST.act(CAST.preloaded(), "add_favorite", {"folder": "junk"})
    links = favorite_links(mail, "junk", ROOT)
    assert [link.folder for link in links] == [*DEFAULT_FAVORITES, "junk"]
    junk = links[-1]
    assert (junk.badge, junk.current, junk.url) == (1, True, ROOT + "?folder=junk")


def test_every_folder_says_whether_it_is_a_favorite():
    starred = {link.folder for link in folder_links(CAST.preloaded(), None, ROOT) if link.favorite}
    assert starred == set(DEFAULT_FAVORITES)

"""MicroMail shows the sender's generated face: left of each row of the message list (rows come
from the fragment cache) and beside the From line of the reading pane, as decoration only."""

from __future__ import annotations

import re

import pytest

pytestmark = pytest.mark.django_db

PRIYA_FACE = '<img class="avatar" src="/media/avatars/priya-nair.svg" alt=""'
_ROW = re.compile(r'<li class="message[ "].*?</li>', re.DOTALL)


def rows_by_id(html: str) -> dict[str, str]:
    return {re.search(r'id="select-([^"]+)"', row).group(1): row for row in _ROW.findall(html)}


def test_each_row_shows_its_senders_face_inside_the_row_link(mail_url, browser):
    rows = rows_by_id(browser.get(mail_url("?folder=inbox")).content.decode())
    row = rows["budget-review"]
    assert f'{PRIYA_FACE} width="32" height="32">' in row
    link = row[row.index('<a class="row-link"') :]
    assert link.index(PRIYA_FACE) < link.index('<span class="sender">')


def test_a_cached_row_still_shows_the_face(mail_url, browser):
    first = rows_by_id(browser.get(mail_url("?folder=inbox")).content.decode())
    again = rows_by_id(browser.get(mail_url("?folder=inbox")).content.decode())
    assert again["budget-review"] == first["budget-review"]
    assert PRIYA_FACE in again["budget-review"]


def test_the_reading_pane_shows_the_senders_face_beside_from(mail_url, browser):
    html = browser.get(mail_url("?folder=inbox&email=budget-review")).content.decode()
    pane = html[html.index('id="reading-pane"') :]
    card = pane[pane.index('<div class="sender-card">') : pane.index("</dl>")]
    assert f'{PRIYA_FACE} width="40" height="40">' in card
    assert "<dt>From</dt>" in card


def test_the_top_bar_shows_the_self_users_face(mail_url, browser):
    html = browser.get(mail_url("?folder=inbox")).content.decode()
    assert '<img class="avatar" src="/media/avatars/robin-vale.svg" alt=""' in html


def test_faces_add_nothing_to_the_rows_accessible_text(mail_url, browser):
    row = rows_by_id(browser.get(mail_url("?folder=inbox")).content.decode())["budget-review"]
    images = re.findall(r"<img [^>]*>", row)
    assert images and all(' alt=""' in image for image in images)

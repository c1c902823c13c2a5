"""Page snapshots as markdown, and the diff blocks wait_for shows the model."""

from __future__ import annotations

import json

from django.test import Client

from apps.browser_agent.snapshot import html_to_markdown
from apps.browser_agent.waiting import unified_diff_blocks

PAGE = """<!DOCTYPE html>
<html><head><title>Inbox</title><style>.row { color: red }</style>
<script>window.secret = "script text"</script></head>
<body>
  <h1>Inbox</h1>
  <svg><text>svg label</text></svg>
  <template><p>template row</p></template>
  <div hidden>hidden banner</div>
  <ul>
    <li>Maya Okonjo — Agenda</li>


    <li>Kevin Lee — Expenses</li>
  </ul>
  <noscript>enable JavaScript</noscript>
</body></html>"""


def rows(count: int, inserted_at: int | None = None) -> str:
    lines = [f"- Message {n}: subject {n}" for n in range(count)]
    if inserted_at is not None:
        lines.insert(inserted_at, "- Message new: from Kevin Lee")
    return "\n".join(["# Inbox", "", *lines, ""])


def test_markdown_keeps_the_visible_text():
    markdown = html_to_markdown(PAGE)
    assert "# Inbox" in markdown
    assert "- Maya Okonjo — Agenda" in markdown
    assert "- Kevin Lee — Expenses" in markdown


def test_markdown_drops_what_is_never_on_screen():
    markdown = html_to_markdown(PAGE)
    for invisible in (
        "color: red",
        "script text",
        "svg label",
        "template row",
        "hidden banner",
        "enable JavaScript",
    ):
        assert invisible not in markdown


def test_markdown_collapses_blank_lines_and_trailing_spaces():
    markdown = html_to_markdown(PAGE)
    assert "\n\n\n" not in markdown
    assert all(line == line.rstrip() for line in markdown.splitlines())


def test_two_renders_of_the_same_mailbox_give_the_same_markdown(db):
    # A real page carries a fresh CSRF token per render: none of it may reach the snapshot.
    client = Client()
    run = client.post(
        "/api/runs/",
        json.dumps({"scenario": "micromail-sender-absolute-passive", "clock_mode": "virtual"}),
        content_type="application/json",
    ).json()
    inbox = f"/r/{run['token']}/micromail/"
    first = html_to_markdown(client.get(inbox).content.decode())
    second = html_to_markdown(Client().get(inbox).content.decode())
    assert "# Inbox" in first
    assert first == second


def test_the_same_text_has_no_blocks():
    assert unified_diff_blocks(rows(20), rows(20)) == []


def test_an_inserted_row_is_one_block_with_its_context():
    [block] = unified_diff_blocks(rows(20), rows(20, inserted_at=10))
    lines = block.splitlines()
    assert "+- Message new: from Kevin Lee" in lines
    assert [line for line in lines if line[0] in "+-"] == ["+- Message new: from Kevin Lee"]
    assert {line[0] for line in lines} == {" ", "+"}


def test_distant_changes_are_separate_blocks_in_page_order():
    current = rows(40).replace("subject 3\n", "subject three\n").replace("subject 30", "later")
    first, second = unified_diff_blocks(rows(40), current)
    assert "+- Message 3: subject three" in first.splitlines()
    assert "+- Message 30: later" in second.splitlines()


def test_a_block_carries_no_header_or_position():
    current = rows(20).replace("subject 5", "subject five")
    for block in unified_diff_blocks(rows(20), current):
        assert not any(line.startswith(("@@", "---", "+++")) for line in block.splitlines())


def test_a_block_pushed_down_by_an_insertion_above_is_the_same_block():
    base = rows(40)
    changed = base.replace("subject 30", "later")
    [alone] = unified_diff_blocks(base, changed)
    pushed_down = changed.replace("- Message 2:", "- Message new: from Kevin Lee\n- Message 2:")
    assert alone in unified_diff_blocks(base, pushed_down)


def test_a_closed_menu_shows_its_summary_only_an_open_one_everything():
    menu = "<details{}><summary>Move to</summary>loose words<ul><li>Archive</li></ul></details>"
    closed = html_to_markdown(menu.format(""))
    assert "Move to" in closed
    assert "Archive" not in closed and "loose words" not in closed
    opened = html_to_markdown(menu.format(" open"))
    assert "Archive" in opened and "loose words" in opened

"""The helpers every environment's decide() uses: fresh logged ids, required text, 404s."""

from __future__ import annotations

import re
from types import SimpleNamespace

import pytest

from apps.kit.deciding import checking, found, new_id, required_text
from events.registry import ActionRejected


def test_a_new_id_is_prefixed_and_never_repeats():
    ids = {new_id("draft") for _ in range(1000)}
    assert len(ids) == 1000
    assert all(re.fullmatch(r"draft-[0-9a-f]{12}", i) for i in ids)


def test_required_text_is_stripped_and_blank_is_a_400_naming_the_field():
    assert required_text({"text": "  hi  "}, "text") == "hi"
    for payload in ({}, {"text": None}, {"text": " \n "}):
        with pytest.raises(ActionRejected, match="payload field 'text' is empty") as raised:
            required_text(payload, "text")
        assert raised.value.status == 400


def test_an_unknown_item_is_a_404_that_says_where_it_was_looked_for():
    assert found({"p1": "post"}, "p1", "post", "on MicroGram") == "post"
    with pytest.raises(ActionRejected) as raised:
        found({"p1": "post"}, "p2", "post", "on MicroGram")
    assert (str(raised.value), raised.value.status) == ("no post 'p2' on MicroGram", 404)


def test_checking_logs_the_payload_as_it_came_when_the_item_is_there():
    decide = checking("posts", "post_id", "post", "on this network")
    state = SimpleNamespace(posts={"p1": object()})
    payload = {"post_id": "p1", "extra": 1}
    assert decide(state, payload) is payload
    with pytest.raises(ActionRejected, match="no post 'p9' on this network"):
        decide(state, {"post_id": "p9"})

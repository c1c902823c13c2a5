"""Payload schemas (events/schemas.py): what validate_payload accepts, and its one-line errors."""

from __future__ import annotations

from typing import Literal

import pytest
from pydantic import Field

from events.registry import PayloadError as ReexportedPayloadError
from events.schemas import Payload, PayloadError, describe, schema_fields, validate_payload


class Filter(Payload):
    tags: list[str]
    colour: Literal["red", "blue"] | None = None


class Search(Payload):
    """A made-up action payload that uses every kind of field."""

    email_id: str = Field(description="id of a message")
    folder: Literal["inbox", "sent", "drafts"] = "inbox"
    labels: list[str] | None = None
    filter: Filter | None = None
    weight: float = 1.0
    limit: int = Field(10, ge=1)


def problem(payload: object, schema: type[Payload] = Search) -> str:
    with pytest.raises(PayloadError) as raised:
        validate_payload(schema, payload, what="action search")
    return str(raised.value)


def test_a_list_of_strings_is_accepted():
    payload = {"email_id": "m1", "labels": ["work", "urgent"]}
    assert validate_payload(Search, payload, what="action search") == payload


def test_a_list_element_of_the_wrong_type_is_named_by_its_position():
    assert problem({"email_id": "m1", "labels": ["work", 7]}) == (
        "action search: payload field 'labels[1]' must be string, got 7"
    )


def test_an_optional_field_may_be_left_out():
    assert validate_payload(Search, {"email_id": "m1"}, what="action search") == {"email_id": "m1"}


def test_an_optional_field_of_the_wrong_type_names_the_type_and_null():
    assert problem({"email_id": "m1", "labels": "work"}) == (
        "action search: payload field 'labels' must be list of strings or null, got 'work'"
    )


def test_a_required_field_names_its_type():
    assert problem({}) == "action search: payload field 'email_id' is required (string)"


def test_a_wrong_type_names_the_field_and_the_value():
    assert (
        problem({"email_id": 5}) == "action search: payload field 'email_id' must be string, got 5"
    )


def test_an_error_inside_a_nested_object_names_the_full_location():
    assert problem({"email_id": "m1", "filter": {"tags": ["a", "b", 3]}}) == (
        "action search: payload field 'filter.tags[2]' must be string, got 3"
    )


def test_a_missing_field_of_a_nested_object_names_the_full_location():
    assert problem({"email_id": "m1", "filter": {}}) == (
        "action search: payload field 'filter.tags' is required (list of strings)"
    )


def test_a_value_outside_a_literal_lists_the_allowed_values():
    assert problem({"email_id": "m1", "folder": "spam"}) == (
        "action search: payload field 'folder' is 'spam'; allowed: inbox, sent, drafts"
    )


def test_unknown_fields_are_listed_with_the_allowed_ones():
    assert problem({"email_id": "m1", "size": 2, "colour": "red"}) == (
        "action search: unknown payload field(s) colour, size; "
        "allowed: email_id, folder, labels, filter, weight, limit"
    )


def test_unknown_fields_of_a_nested_object_name_the_object():
    assert problem({"email_id": "m1", "filter": {"tags": [], "size": 2}}) == (
        "action search: unknown payload field(s) size in 'filter'; allowed: tags, colour"
    )


def test_a_schema_without_fields_allows_none():
    assert problem({"n": 1}, schema=Payload) == (
        "action search: unknown payload field(s) n; allowed: none"
    )


def test_a_bool_is_not_an_integer():
    assert problem({"email_id": "m1", "limit": True}) == (
        "action search: payload field 'limit' must be integer, got True"
    )


def test_a_bool_is_not_a_number():
    assert problem({"email_id": "m1", "weight": False}) == (
        "action search: payload field 'weight' must be number, got False"
    )


def test_a_numeric_string_is_not_a_number():
    assert problem({"email_id": "m1", "weight": "2.5"}) == (
        "action search: payload field 'weight' must be number, got '2.5'"
    )


def test_an_integer_is_accepted_as_a_number():
    payload = {"email_id": "m1", "weight": 2}
    assert validate_payload(Search, payload, what="action search")["weight"] == 2


def test_a_constraint_reports_pydantics_reason_in_our_words():
    assert problem({"email_id": "m1", "limit": 0}) == (
        "action search: payload field 'limit' must be greater than or equal to 1, got 0"
    )


def test_the_payload_is_returned_as_given_not_as_a_model_dump():
    payload = {"weight": 2, "email_id": "m1"}
    returned = validate_payload(Search, payload, what="action search")
    assert returned is payload
    assert list(returned) == ["weight", "email_id"] and type(returned["weight"]) is int


def test_a_payload_that_is_not_an_object_is_rejected_with_its_type():
    assert problem(["m1"]) == "action search: payload must be an object, got list"


def test_payload_error_is_still_importable_from_the_registry():
    assert ReexportedPayloadError is PayloadError


def test_describe_names_types_in_words():
    assert [describe(t) for t in (str, int, float, bool, list[int], Filter | None)] == [
        "string",
        "integer",
        "number",
        "boolean",
        "list of integers",
        "object (tags, colour) or null",
    ]


def test_schema_fields_give_type_requiredness_and_help():
    assert schema_fields(Search)[:3] == [
        ("email_id", "string", True, "id of a message"),
        ("folder", "one of: inbox, sent, drafts", False, ""),
        ("labels", "list of strings or null", False, ""),
    ]

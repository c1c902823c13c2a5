"""The catalog loader: our fixtures, the original catalogs, wildcards, hashes, bad input."""

from __future__ import annotations

import pytest

from events.catalog import CatalogError, read_catalog


def test_our_fixtures_load_with_a_single_self_user(settings):
    catalog = read_catalog(settings.SENTINEL_CATALOG_DIR)
    assert catalog.self_user["email"] == "ctaylor@mymicromail.com"
    assert sum(1 for u in catalog.users.values() if u.get("isSelf")) == 1
    assert len(catalog.table("micromail", "emails")) >= 150


def test_wildcard_expands_to_every_id_in_catalog_order(settings):
    catalog = read_catalog(settings.SENTINEL_CATALOG_DIR)
    every = catalog.expand("micromail", "emails", ["*"])
    assert every == list(catalog.table("micromail", "emails"))
    assert catalog.expand("micromail", "emails", ["*", "base-01"]) == [
        "*",
        "base-01",
    ]  # mixed: not expanded


@pytest.mark.upstream
def test_the_original_catalogs_load(upstream_dir):
    catalog = read_catalog(upstream_dir / "catalogs")
    assert len(catalog.users) == 100
    assert len(catalog.table("micromail", "emails")) == 260
    assert len(catalog.content_hash) == 64


def test_the_content_hash_changes_with_the_content(tmp_path):
    (tmp_path / "users.json").write_text('[{"id": "user000", "isSelf": true}]')
    (tmp_path / "mail").mkdir()
    (tmp_path / "mail" / "emails.jsonl").write_text('{"id": "a"}\n\n{"id": "b"}\n')
    first = read_catalog(tmp_path)
    assert list(first.table("mail", "emails")) == ["a", "b"]
    (tmp_path / "mail" / "emails.jsonl").write_text('{"id": "a"}\n')
    assert read_catalog(tmp_path).content_hash != first.content_hash


@pytest.mark.parametrize(
    "content,needle",
    [
        ('{"id": "a"}\nnot json\n', ":2: invalid JSON"),
        ('{"id": "a"}\n{"id": "a"}\n', "duplicate id"),
        ("[1, 2]\n", "expected a JSON object"),
    ],
)
def test_bad_catalog_lines_name_the_file_and_line(tmp_path, content, needle):
    (tmp_path / "mail").mkdir()
    (tmp_path / "mail" / "emails.jsonl").write_text(content)
    with pytest.raises(CatalogError, match=needle):
        read_catalog(tmp_path)

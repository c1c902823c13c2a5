"""Load a catalog in the SentinelBench format, once per process.

A catalog directory holds `users.json`, `entities.json` and one folder per environment with
`<table>.jsonl` (one record per line) or `<name>.json` files. It is immutable at run time; a
run records the directory and a content hash so a result can always be traced to its content.
"""

from __future__ import annotations

import functools
import hashlib
import json
import threading
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any, TypeVar

WILDCARD = ["*"]


class CatalogError(ValueError):
    pass


@dataclass(frozen=True)
class Catalog:
    directory: Path
    content_hash: str
    users: Mapping[str, Mapping[str, Any]]
    entities: Mapping[str, Mapping[str, Any]]
    # environment → table name → id → record (in file order)
    tables: Mapping[str, Mapping[str, Mapping[str, Mapping[str, Any]]]]
    # environment → name → raw JSON document (for `<name>.json` files such as price traces)
    documents: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)

    @property
    def self_user(self) -> Mapping[str, Any] | None:
        return next((u for u in self.users.values() if u.get("isSelf")), None)

    def table(self, environment: str, name: str) -> Mapping[str, Mapping[str, Any]]:
        return self.tables.get(environment, {}).get(name, MappingProxyType({}))

    def expand(self, environment: str, name: str, ids: Iterable[str] | None) -> list[str]:
        """`["*"]` exactly means every id of the table (in catalog order); other lists as given."""
        ids = list(ids or [])
        if ids == WILDCARD:
            return list(self.table(environment, name))
        return ids

    def missing_ids(self, environment: str, name: str, ids: Iterable[str]) -> list[str]:
        table = self.table(environment, name)
        return [i for i in ids if i != "*" and i not in table]

    def index(self, build: Callable[[Catalog], T]) -> T:
        """`build(self)` computed once per catalog (an index of attachments by email, of
        tracks by artist…): a catalog is immutable, so what is derived from it is too."""
        with _index_lock:
            indexes = _indexes.setdefault((self.directory, self.content_hash), {})
            if build not in indexes:
                indexes[build] = build(self)
            return indexes[build]


T = TypeVar("T")
_indexes: dict[tuple[Path, str], dict[Callable, Any]] = {}
_index_lock = threading.Lock()


def _read_json(path: Path) -> Any:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise CatalogError(
            f"{path}: invalid JSON at line {exc.lineno} column {exc.colno}: {exc.msg}"
        ) from None


def _read_jsonl(path: Path) -> dict[str, Mapping[str, Any]]:
    records: dict[str, Mapping[str, Any]] = {}
    with path.open(encoding="utf-8") as fh:
        for number, line in enumerate(fh, 1):
            line = line.strip()
            if not line:
                continue  # upstream's builder skips blank lines too
            try:
                record = json.loads(line)
            except json.JSONDecodeError as exc:
                raise CatalogError(f"{path}:{number}: invalid JSON: {exc.msg}") from None
            if not isinstance(record, dict):
                raise CatalogError(
                    f"{path}:{number}: expected a JSON object, got {type(record).__name__}"
                )
            # Records are keyed by `id` (or `symbol` for stocks). A few tables (e.g. the original
            # microgram suggestions) have neither: their 1-based line number keys them, as the
            # original loader's "order" column did.
            key = record.get("id", record.get("symbol", f"line-{number}"))
            if str(key) in records:
                raise CatalogError(f"{path}:{number}: duplicate id {key!r}")
            records[str(key)] = MappingProxyType(record)
    return records


def _by_id(records: Any, path: Path) -> dict[str, Mapping[str, Any]]:
    if not isinstance(records, list):
        raise CatalogError(f"{path}: expected a JSON array of records")
    return {str(r["id"]): MappingProxyType(r) for r in records if isinstance(r, dict) and "id" in r}


def _content_hash(directory: Path) -> str:
    digest = hashlib.sha256()
    for path in sorted(
        p for p in directory.rglob("*") if p.is_file() and p.suffix in (".json", ".jsonl")
    ):
        digest.update(str(path.relative_to(directory)).encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
    return digest.hexdigest()


def read_catalog(directory: Path) -> Catalog:
    directory = Path(directory).resolve()
    if not directory.is_dir():
        raise CatalogError(f"catalog directory {directory} does not exist")
    users_path, entities_path = directory / "users.json", directory / "entities.json"
    users = _by_id(_read_json(users_path), users_path) if users_path.exists() else {}
    entities = _by_id(_read_json(entities_path), entities_path) if entities_path.exists() else {}
    tables: dict[str, dict] = {}
    documents: dict[str, dict] = {}
    for env_dir in sorted(p for p in directory.iterdir() if p.is_dir()):
        for path in sorted(env_dir.iterdir()):
            if path.suffix == ".jsonl":
                tables.setdefault(env_dir.name, {})[path.stem] = MappingProxyType(_read_jsonl(path))
            elif path.suffix == ".json":
                documents.setdefault(env_dir.name, {})[path.stem] = _read_json(path)
    return Catalog(
        directory=directory,
        content_hash=_content_hash(directory),
        users=MappingProxyType(users),
        entities=MappingProxyType(entities),
        tables=MappingProxyType({k: MappingProxyType(v) for k, v in tables.items()}),
        documents=MappingProxyType(documents),
    )


_cache: dict[Path, Catalog] = {}
_lock = threading.Lock()


@functools.lru_cache(maxsize=64)
def _resolved(directory: str) -> Path:
    # Every run's creation and first fold ask for their catalog: resolving the path each time
    # made a system call per path component.
    return Path(directory).resolve()


def load_catalog(directory: Path | str | None = None) -> Catalog:
    """The catalog of `directory` (default SENTINEL_CATALOG_DIR), read once per process."""
    if directory is None:
        from django.conf import settings

        directory = settings.SENTINEL_CATALOG_DIR
    key = _resolved(str(directory))
    catalog = _cache.get(key)
    if catalog is None:
        with _lock:
            catalog = _cache.get(key)
            if catalog is None:
                catalog = _cache[key] = read_catalog(key)
    return catalog

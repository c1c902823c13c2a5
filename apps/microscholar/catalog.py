"""Catalog records (SentinelBench format) → papers, alerts, scholar profiles and co-authors.

Tables in `microscholar/`: `papers.jsonl`, `alerts.jsonl`, `coauthors.jsonl` (the original's
three, whose record shapes are accepted as they are) and, in our catalog, `scholars.jsonl` (the
profile of each person who has one; the original keeps that as a `microscholar` block on the
user record, also accepted). Our papers may add `versions` and `citationGrowth`
(`[[seconds after indexing, count], …]`: how "Cited by" climbs while a run lasts); without it a
count stays as catalogued, which is the original's behaviour.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, NamedTuple

from apps.kit.arrivals import Stamp
from apps.kit.feeds import from_catalog
from apps.kit.records import Record, read
from apps.kit.streaming import whole
from apps.kit.waypoints import growing
from apps.microscholar.state import ENVIRONMENT, Alert, Paper, Scholar


@from_catalog(ENVIRONMENT, "papers")
def catalog_paper(scholar: Scholar, paper_id: str, record: Record, stamp: Stamp) -> Paper:
    """The paper as indexed now."""
    # The catalogued count, flat until the paper is indexed, then along its growth points.
    citations = growing(float(whole(record.get("citedBy"))), record.get("citationGrowth"), stamp.at)
    return read(Paper, record, id=paper_id, citations=citations, indexed_at=float(stamp.at))


@from_catalog(ENVIRONMENT, "alerts")
def catalog_alert(
    scholar: Scholar, alert_id: str, record: Record, stamp: Stamp
) -> tuple[Alert, bool]:
    """The alert and whether it is read: a preloaded one as catalogued, a new one unread."""
    alert = read(Alert, record, id=alert_id, arrived_at=float(stamp.at))
    return alert, stamp.preloaded and bool(record.get("isRead", False))


@dataclass(frozen=True)
class Profile:
    """A scholar's public profile (the header of their citations page)."""

    user_id: str
    name: str
    affiliation: str
    email_domain: str
    interests: tuple[str, ...]
    is_self: bool = False


def _profile(user_id: str, user: Mapping, affiliation: str, domain: str, interests) -> Profile:
    name, is_self = str(user.get("name", user_id)), bool(user.get("isSelf", False))
    return Profile(
        user_id, name, affiliation, domain, tuple(str(i) for i in interests or ()), is_self
    )


def profiles(catalog: Any) -> Mapping[str, Profile]:
    """Every person with a scholar profile: ours from `scholars.jsonl`, the original's from the
    user records' `microscholar` blocks (computed once per catalog)."""
    found: dict[str, Profile] = {}
    for user_id, user in catalog.users.items():
        block = user.get("microscholar")
        if isinstance(block, Mapping):
            affiliation = ", ".join(
                str(x) for x in (block.get("title"), block.get("affiliation")) if x
            )
            domain = str(block.get("email") or user.get("email") or "").partition("@")[2]
            found[user_id] = _profile(user_id, user, affiliation, domain, block.get("interests"))
    for user_id, record in catalog.table(ENVIRONMENT, "scholars").items():
        user = catalog.users.get(user_id) or {}
        affiliation = str(record.get("affiliation", ""))
        email = str(user.get("email", ""))
        domain = str(record.get("emailDomain") or email.partition("@")[2])
        found[user_id] = _profile(user_id, user, affiliation, domain, record.get("interests"))
    return found


def coauthors(catalog: Any) -> Mapping[str, tuple[str, ...]]:
    """Person → co-authors, in catalog order, from the pairs of `coauthors.jsonl` (both ways).
    All relations are always known (the original loads them whatever the preload says)."""
    found: dict[str, list[str]] = {}
    for one, two, _ in coauthor_pairs(catalog):
        if one and two:
            found.setdefault(one, []).append(two)
            found.setdefault(two, []).append(one)
    return {k: tuple(dict.fromkeys(v)) for k, v in found.items()}


class Coauthorship(NamedTuple):
    """A relation of `coauthors.jsonl` (authorId1, authorId2, sharedPapers)."""

    one: str
    two: str
    shared: tuple[str, ...]


def coauthor_pairs(catalog: Any) -> tuple[Coauthorship, ...]:
    return tuple(
        Coauthorship(
            str(r.get("authorId1", "")),
            str(r.get("authorId2", "")),
            tuple(str(p) for p in r.get("sharedPapers") or ()),
        )
        for r in catalog.table(ENVIRONMENT, "coauthors").values()
    )


def person_name(catalog: Any, user_id: str) -> str:
    return str((catalog.users.get(user_id) or {}).get("name") or user_id)

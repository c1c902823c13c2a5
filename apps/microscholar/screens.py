"""What each screen shows, as pure functions of (state, URL query, now, root).

Which papers a screen lists depends on the state only and is memoised per state; the rows are
then read at `now`, because "Cited by N" moves with the clock (each paper's `Waypoints`).
Templates only lay these values out; tests check screens without HTML.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any
from urllib.parse import quote, urlencode

from apps.kit.derived import per_state
from apps.microscholar import search
from apps.microscholar import state as index
from apps.microscholar.catalog import Profile, coauthors, person_name, profiles
from apps.microscholar.query import PER_PAGE, AlertsQuery, ProfileQuery, SearchQuery
from apps.microscholar.state import Alert, Paper, Scholar

SNIPPET_LENGTH = 220
RELATED_SHOWN = 5
CHART_YEARS = 8
# (value, label) of each sort or filter link
SORT_LINKS = (("relevance", "Sort by relevance"), ("date", "Sort by date"))
PROFILE_SORT_LINKS = (("cited", "Cited by"), ("pubdate", "Year"))
ALERT_FILTER_LINKS = (("all", "All alerts"), ("unread", "Unread"))
ALERT_ICONS = {"citation": "quote", "new_paper": "file-plus", "keyword": "search"}


@dataclass(frozen=True)
class AuthorLink:
    name: str
    url: str | None  # the scholar's profile, when they have one


@dataclass(frozen=True)
class Row:
    """One paper as a result entry (inputs of the row fragment: hashable, read at `now`). What
    it does not say itself (id, title, source, year, versions…) is its paper's."""

    paper: Paper
    url: str
    cite_url: str
    authors: tuple[AuthorLink, ...]
    snippet: str
    cited_by: int
    saved: bool

    def __getattr__(self, name: str) -> Any:  # only called for what the row itself lacks
        if name.startswith("__"):  # copy and pickle probe before `paper` is set
            raise AttributeError(name)
        return getattr(self.paper, name)


@dataclass(frozen=True)
class Option:
    """A link choosing one value of the URL (a sort, a filter, a page of results)."""

    label: str
    url: str
    current: bool


def choices(query, param: str, labels, at: str) -> tuple[Option, ...]:
    """One link per (value, label) of `param`, to the screen `at` with the query given that
    value; the value the query has now is the current one."""
    return tuple(
        Option(
            label, at + query.but(**{param: value}).querystring(), getattr(query, param) == value
        )
        for value, label in labels
    )


def short_snippet(text: str) -> str:
    """The first couple of lines of an abstract, cut at a word, as a result entry shows it."""
    flat = " ".join(text.split())
    if len(flat) <= SNIPPET_LENGTH:
        return flat
    return flat[:SNIPPET_LENGTH].rsplit(" ", 1)[0] + " …"


def profile_url(root: str, user_id: str) -> str:
    return f"{root}citations?{urlencode({'user': user_id})}"


def paper_url(root: str, paper_id: str) -> str:
    return f"{root}papers/{quote(paper_id)}"


def author_links(scholar: Scholar, paper: Paper, root: str) -> tuple[AuthorLink, ...]:
    """The display names, each linked to a profile when the author id at its place has one."""
    known = scholar.catalog.index(profiles)
    shown = [a.strip() for a in paper.authors.split(",") if a.strip()]
    ids = paper.author_ids if len(paper.author_ids) == len(shown) else ()
    return tuple(
        AuthorLink(name, profile_url(root, ids[n]) if ids and ids[n] in known else None)
        for n, name in enumerate(shown)
    )


def row(scholar: Scholar, paper_id: str, now: float, root: str, *, full: bool = False) -> Row:
    paper = scholar.papers[paper_id]
    url = paper_url(root, paper_id)
    return Row(
        paper=paper,
        url=url,
        cite_url=url + "/cite",
        authors=author_links(scholar, paper, root),
        snippet=paper.snippet if full else short_snippet(paper.snippet),
        cited_by=paper.cited_by(now),
        saved=scholar.is_saved(paper_id),
    )


def rows(scholar: Scholar, ids: Iterable[str], now: float, root: str) -> tuple[Row, ...]:
    return tuple(row(scholar, i, now, root) for i in ids)


# --- search and the home page ---------------------------------------------------------------------


@per_state()
def matching(scholar: Scholar, q: str, since: int | None, until: int | None, sort: str) -> tuple:
    """Ids for a search: by relevance (`search.ranked`), or newest year first."""

    def in_range(paper: Paper) -> bool:
        return (since is None or paper.year >= since) and (until is None or paper.year <= until)

    ids = search.ranked(filter(in_range, index.listed(scholar)), q)
    if sort == "date":
        order = {paper_id: n for n, paper_id in enumerate(index.newest_first(scholar, ids))}
        ids = sorted(ids, key=lambda i: (-scholar.papers[i].year, order[i]))
    return tuple(ids)


@per_state()
def recommended(scholar: Scholar) -> tuple[str, ...]:
    """Home page recommendations: every indexed paper, the most recently indexed first."""
    return tuple(index.newest_first(scholar, (p.id for p in index.listed(scholar))))


@dataclass(frozen=True)
class SearchScreen:
    total: int
    ids: tuple[str, ...]  # the ids of this page of results
    years: tuple[Option, ...]
    sorts: tuple[Option, ...]
    pages: tuple[Option, ...]
    custom_range: bool
    previous_url: str | None
    next_url: str | None


def since_years(this_year: int) -> tuple[str, ...]:
    """Google Scholar's "Since <year>" choices: this year, last year, 4 years back."""
    return tuple(str(y) for y in (this_year, this_year - 1, this_year - 4))


def year_options(query: SearchQuery, this_year: int, root: str) -> tuple[Option, ...]:
    """ "Any time" and the "Since <year>" choices."""
    return tuple(
        Option(
            f"Since {value}" if value else "Any time",
            root + query.but(as_ylo=value, as_yhi="", start="").querystring(),
            query.as_ylo == value and not query.as_yhi,
        )
        for value in ("", *since_years(this_year))
    )


def search_screen(scholar: Scholar, query: SearchQuery, this_year: int, root: str) -> SearchScreen:
    """Results for `query` (a query without `q` lists the recommended articles)."""
    if query.q:
        found = matching(scholar, query.q, query.since, query.until, query.sort)
    else:
        found = recommended(scholar)
    offset = min(query.offset, max(0, (len(found) - 1) // PER_PAGE * PER_PAGE))
    starts = range(0, len(found), PER_PAGE)  # the first result of each page
    pages = tuple(
        Option(
            str(n),
            root + query.but(start=str(start) if start else "").querystring(),
            start == offset,
        )
        for n, start in enumerate(starts, 1)
    )
    pages = pages if len(pages) > 1 else ()
    current = offset // PER_PAGE
    return SearchScreen(
        total=len(found),
        ids=tuple(found[offset : offset + PER_PAGE]),
        years=year_options(query, this_year, root),
        sorts=choices(query.but(start=""), "sort", SORT_LINKS, root),
        pages=pages,
        custom_range=bool(query.as_yhi)
        or (bool(query.as_ylo) and query.as_ylo not in since_years(this_year)),
        previous_url=pages[current - 1].url if pages and current > 0 else None,
        next_url=pages[current + 1].url if pages and current + 1 < len(pages) else None,
    )


# --- a paper and its related articles ---------------------------------------------------------------


@per_state()
def related(scholar: Scholar, paper_id: str) -> tuple[str, ...]:
    """Other indexed papers closest to this one's title (any of its meaningful words)."""
    paper = scholar.papers[paper_id]
    others = [p for p in index.listed(scholar) if p.id != paper_id]
    return tuple(search.similar(others, paper.title)[:RELATED_SHOWN])


# --- a scholar's profile ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Bar:
    """One year of the citation history chart, in the SVG's coordinates (bars stand on y=108)."""

    year: int
    count: int
    x: int
    y: int
    height: int


@dataclass(frozen=True)
class Metric:
    label: str
    all: int
    recent: int


@dataclass(frozen=True)
class Coauthor:
    name: str
    affiliation: str
    url: str | None


@dataclass(frozen=True)
class ProfileScreen:
    profile: Profile
    articles: tuple[Row, ...]
    metrics: tuple[Metric, ...]
    since: int
    bars: tuple[Bar, ...]
    coauthors: tuple[Coauthor, ...]
    sorts: tuple[Option, ...]


@per_state()
def authored(scholar: Scholar, user_id: str) -> tuple[str, ...]:
    return tuple(p.id for p in index.listed(scholar) if user_id in p.author_ids)


def h_index(counts: Iterable[int]) -> int:
    ordered = sorted(counts, reverse=True)
    return sum(1 for n, c in enumerate(ordered, 1) if c >= n)


def yearly(count: int, published: int, this_year: int) -> dict[int, int]:
    """A paper's citations spread over the years since it appeared, growing each year (the
    original draws a made-up chart too; this one at least sums to the counts shown)."""
    years = list(range(min(published, this_year), this_year + 1))
    weights = list(range(1, len(years) + 1))
    shares = {y: count * w // sum(weights) for y, w in zip(years, weights, strict=True)}
    shares[this_year] += count - sum(shares.values())
    return shares


def citation_history(cited: list[tuple[int, int]], this_year: int) -> tuple[Bar, ...]:
    totals = dict.fromkeys(range(this_year - CHART_YEARS + 1, this_year + 1), 0)
    for count, year in cited:
        for y, n in yearly(count, year, this_year).items():
            if y in totals:
                totals[y] += n
    top = max(totals.values(), default=0) or 1
    bars = []
    for n, (year, count) in enumerate(totals.items()):
        height = round(count * 100 / top)
        bars.append(Bar(year, count, 6 + n * 32, 108 - height, height))
    return tuple(bars)


def profile_screen(
    scholar: Scholar, query: ProfileQuery, now: float, this_year: int, root: str
) -> ProfileScreen:
    """`query.user` must have a profile (the view checks)."""
    catalog = scholar.catalog
    known = catalog.index(profiles)
    newest = query.sortby == "pubdate"
    articles = tuple(
        sorted(
            rows(scholar, authored(scholar, query.user), now, root),
            key=lambda r: -r.year if newest else -r.cited_by,
        )
    )
    since = this_year - 5
    recent = [
        sum(n for y, n in yearly(r.cited_by, r.year, this_year).items() if y >= since)
        for r in articles
    ]
    counts = [r.cited_by for r in articles]
    metrics = (
        Metric("Citations", sum(counts), sum(recent)),
        Metric("h-index", h_index(counts), h_index(recent)),
        Metric("i10-index", sum(1 for c in counts if c >= 10), sum(1 for c in recent if c >= 10)),
    )
    people = tuple(
        Coauthor(
            person_name(catalog, other),
            known[other].affiliation if other in known else "",
            profile_url(root, other) if other in known else None,
        )
        for other in catalog.index(coauthors).get(query.user, ())
    )
    return ProfileScreen(
        profile=known[query.user],
        articles=articles,
        metrics=metrics,
        since=since,
        bars=citation_history([(r.cited_by, r.year) for r in articles], this_year),
        coauthors=people,
        sorts=choices(query, "sortby", PROFILE_SORT_LINKS, root + "citations"),
    )


def my_profile_id(scholar: Scholar) -> str | None:
    me = scholar.catalog.self_user
    return str(me["id"]) if me and str(me["id"]) in scholar.catalog.index(profiles) else None


# --- library and alerts ------------------------------------------------------------------------------


@per_state()
def library(scholar: Scholar) -> tuple[str, ...]:
    return tuple(index.newest_first(scholar, index.saved_ids(scholar)))


@dataclass(frozen=True)
class AlertRow:
    alert: Alert
    is_read: bool
    icon: str
    paper_url: str | None


@dataclass(frozen=True)
class AlertsScreen:
    query: AlertsQuery
    rows: tuple[AlertRow, ...]
    unread: int
    filters: tuple[Option, ...]


@per_state()
def alerts_screen(scholar: Scholar, query: AlertsQuery, root: str) -> AlertsScreen:
    newest = sorted(
        enumerate(scholar.alerts.values()), key=lambda na: (na[1].arrived_at, na[0]), reverse=True
    )
    shown = tuple(
        AlertRow(
            alert,
            scholar.alert_read[alert.id],
            ALERT_ICONS.get(alert.type, "bell"),
            # A paper withdrawn since keeps its link, as arXiv keeps the withdrawn paper's page
            # (which says so); one not indexed yet has no page to lead to.
            paper_url(root, alert.related_paper_id)
            if alert.related_paper_id in scholar.papers
            else None,
        )
        for _, alert in newest
        if query.filter == "all" or not scholar.alert_read[alert.id]
    )
    return AlertsScreen(
        query=query,
        rows=shown,
        unread=index.unread_alert_count(scholar),
        filters=choices(query, "filter", ALERT_FILTER_LINKS, root + "alerts"),
    )

"""The MicroGram pages worth timing (`manage.py bench_pages --env microgram`), from the state.

A pure function of the state: every screen, with an open post, story, thread and profile, a
longer feed and the searches. Paths are relative to the environment root.
"""

from __future__ import annotations

from apps.microgram.query import FeedQuery, ProfileQuery, SearchQuery


def sample_pages(gram) -> list[str]:
    """One path per kind of page (opening a post, story or thread views it, once)."""
    pages = [
        "",
        "" + FeedQuery(page="3").querystring(),
        "explore/",
        "explore/" + SearchQuery(q="sunset").querystring(),
        "search/" + SearchQuery(q="an").querystring(),
        "direct/inbox/",
        "activity/",
        f"profile/{gram.me.id}/",
        f"profile/{gram.me.id}/" + ProfileQuery(tab="saved").querystring(),
    ]
    if gram.posts:
        post = next(iter(gram.posts.values()))
        pages += [f"p/{post.id}/", f"profile/{post.author.id}/"]
    if gram.stories:
        pages.append(f"stories/{next(iter(gram.stories))}/")
    if gram.conversations:
        pages.append(f"direct/t/{next(iter(gram.conversations))}/")
    return pages

"""The MicroDin pages worth timing (`manage.py bench_pages --env microdin`), from the state.

A pure function of the network: every screen, with an open job, an open thread, a post, a
profile, a company page and a search. Paths are relative to the environment root.
"""

from __future__ import annotations

from apps.microdin.query import JobsQuery, MessagingQuery, NotificationsQuery, SearchQuery
from apps.microdin.state import Network


def sample_pages(network: Network) -> list[str]:
    """One path per kind of page (opening the thread marks it read, once)."""
    pages = [
        "",
        "mynetwork/",
        "mynetwork/invitations/",
        "jobs/",
        "messaging/",
        "notifications/",
        "notifications/" + NotificationsQuery(filter="unread").querystring(),
        f"in/{network.me.id}/",
    ]
    if network.jobs:
        job = next(reversed(network.jobs.values()))
        pages += [
            "jobs/" + JobsQuery(job=job.id).querystring(),
            f"company/{job.company.id}/",
            "search/" + SearchQuery(q=job.title.split()[0]).querystring(),
        ]
    if network.conversations:
        conversation = next(iter(network.conversations.values()))
        pages += [
            "messaging/" + MessagingQuery(conversation=conversation.id).querystring(),
            f"in/{conversation.other.id}/",
        ]
    if network.posts:
        pages.append(f"feed/update/{next(iter(network.posts))}/")
    return pages

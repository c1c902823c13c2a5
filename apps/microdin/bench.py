"""The MicroDin pages worth timing (`manage.py bench_pages --env microdin`), from the state.

A pure function of the network: every screen, with an open job, an open thread, a post, a
profile, a company page and a search. Paths are relative to the environment root.
"""

from __future__ import annotations

from apps.microdin.query import NotificationsQuery, SearchQuery, job_path, thread_path
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
            job_path(job.id),
            f"company/{job.company.id}/",
            "search/" + SearchQuery(q=job.title.split()[0]).querystring(),
        ]
    if network.conversations:
        conversation = next(iter(network.conversations.values()))
        pages += [thread_path(conversation.id), f"in/{conversation.other.id}/"]
    if network.posts:
        pages.append(f"feed/update/{next(iter(network.posts))}/")
    return pages

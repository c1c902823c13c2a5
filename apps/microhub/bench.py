"""The MicroHub pages worth timing (`manage.py bench_pages --env microhub`), from the state:
every tab, both issue and pull request lists, a search, the busiest issue and pull request, a
folder, a file, a run and the forms."""

from __future__ import annotations

from apps.microhub.state import Hub


def sample_pages(hub: Hub) -> list[str]:
    pages = [
        "",
        "commits/",
        "issues/",
        "issues/?state=closed",
        "issues/?q=sync",
        "issues/?sort=comments",
        "issues/new",
        "pulls/",
        "pulls/?state=closed",
        "actions/",
        "settings",
        "repositories/",
        "new",
        f"users/{hub.self_username}",
    ]
    if hub.issues:
        busiest = max(hub.issues.values(), key=lambda i: len(i.comments))
        pages.append(f"issues/{busiest.id}")
    if hub.prs:
        pages.append(f"pulls/{next(iter(hub.prs))}")
    folder = next((f for f in hub.files.values() if f.is_folder), None)
    if folder:
        pages.append(f"tree/{folder.path}")
    document = next((f for f in hub.files.values() if not f.is_folder), None)
    if document:
        pages.append(f"blob/{document.path}")
    if hub.runs:
        pages.append(f"actions/runs/{next(iter(hub.runs))}")
    return pages

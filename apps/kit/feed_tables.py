"""The `posts` evaluation table of a social feed (MicroDin, MicroGram) in the original's shape."""

from __future__ import annotations

from apps.kit.feeds import post_rows
from apps.kit.tables import Table


def posts_table(text: tuple[str, str], last: tuple[str, str]) -> Table:
    """`posts`: id, author, the post's text (`text`: its column and getter), its likes as shown
    now, and the one column the site adds last (`last`)."""
    return Table(
        "posts",
        post_rows,
        {
            "id TEXT PRIMARY KEY": "post.id",
            "authorId TEXT": "post.author.id",
            text[0]: text[1],
            "likes INTEGER": "likes",
            last[0]: last[1],
        },
    )

"""Evaluation-table columns named after the attribute they hold.

Most of the original's columns are a record's own fields under the same name; `named` declares
those without writing each name twice, and other columns are added beside them:

    Table("issues", lambda hub, now: hub.issues.values(),
          {**named("id TEXT", "number INTEGER", "title TEXT"), "parentId TEXT": "parent_id"})
"""

from __future__ import annotations


def named(*columns: str) -> dict[str, str]:
    """`{column definition: attribute}` for columns whose name is the attribute they read:
    `named("id TEXT", "number INTEGER")` → `{"id TEXT": "id", "number INTEGER": "number"}`."""
    return {column: column.split()[0] for column in columns}

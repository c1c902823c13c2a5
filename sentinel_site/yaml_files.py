"""Reading a user's YAML file (eval_config.yaml, a scripted model's script) with one-line errors."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml


class YamlFileError(ValueError):
    """One line naming the file and what is wrong with it (missing, unreadable, bad YAML)."""


def read_yaml(path: str | Path, what: str = "file") -> Any:
    """The file's data (an empty file is None), or YamlFileError saying where it went wrong;
    `what` names the file in the "not found" line ("config file")."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise YamlFileError(f"{path}: {what} not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise YamlFileError(f"{path}: cannot read: {exc}") from None
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise YamlFileError(f"{path}: invalid YAML{where}: {problem}") from None

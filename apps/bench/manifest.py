"""`results/<NAME>/manifest.json`: what produced a result set.

Written by every `bench run` into its result folder: the config as used (the token left out),
the project's version and commit, the hash of every scenario as the server served it, the
catalog's hash, the machine, when it started and ended, and the counts by outcome of the whole
folder. A result set resumed later keeps one entry per `bench run` in `runs`, so a set that
mixes commits or scenario versions says so.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import subprocess
import sys
from datetime import datetime
from importlib import metadata
from pathlib import Path
from typing import Any

MANIFEST = "manifest.json"
FORMAT = "sentinel-results/1"


def scenario_hash(spec: dict[str, Any]) -> str:
    """sha256 of the scenario as the server served it (canonical JSON)."""
    canonical = json.dumps(spec, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(canonical.encode()).hexdigest()


def project_version(base_dir: Path) -> str:
    """The checkout's pyproject.toml version, else the installed package's (`sentinel`)."""
    try:
        import tomllib

        with open(base_dir / "pyproject.toml", "rb") as fh:
            return str(tomllib.load(fh)["project"]["version"])
    except (OSError, KeyError, ValueError):
        pass
    try:
        return metadata.version("sentinel-environments")
    except metadata.PackageNotFoundError:
        return "unknown"


def git_commit(base_dir: Path) -> str:
    """The commit checked out, `+dirty` when tracked files differ from it; "unknown" outside git."""

    def git(*args: str) -> str:
        done = subprocess.run(
            ["git", *args], cwd=base_dir, capture_output=True, text=True, timeout=30, check=True
        )
        return done.stdout.strip()

    try:
        commit = git("rev-parse", "HEAD")
        dirty = git("status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return commit + ("+dirty" if dirty else "")


def machine() -> dict[str, Any]:
    return {
        "host": platform.node(),
        "platform": platform.platform(),
        "python": sys.version.split()[0],
        "cpus": os.cpu_count(),
        "load_average": [round(x, 2) for x in os.getloadavg()]
        if hasattr(os, "getloadavg")
        else None,
    }


def read_manifest(run_dir: Path) -> dict[str, Any] | None:
    try:
        data = json.loads((run_dir / MANIFEST).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) else None


def build_manifest(
    previous: dict[str, Any] | None,
    *,
    name: str,
    config: dict[str, Any],
    version: str,
    commit: str,
    scenarios: dict[str, str],
    catalog_hashes: list[str],
    started_at: datetime,
    finished_at: datetime,
    counts: dict[str, int],
    host: dict[str, Any],
) -> dict[str, Any]:
    """The manifest after one more `bench run` (pure: the caller reads and writes the file)."""
    this_run = {
        "started_at": started_at.isoformat(timespec="seconds"),
        "finished_at": finished_at.isoformat(timespec="seconds"),
        "version": version,
        "commit": commit,
        "config": config,
        "machine": host,
    }
    runs = [*((previous or {}).get("runs") or []), this_run]
    known = dict((previous or {}).get("scenarios") or {})
    catalogs = sorted({*((previous or {}).get("catalog_hashes") or []), *catalog_hashes})
    return {
        "format": FORMAT,
        "name": name,
        "started_at": runs[0]["started_at"],
        "finished_at": this_run["finished_at"],
        "version": version,
        "commit": commit,
        "config": config,
        "machine": host,
        "scenarios": {**known, **scenarios},
        "catalog_hashes": catalogs,
        "counts": counts,
        "runs": runs,
    }


def write_manifest(run_dir: Path, manifest: dict[str, Any]) -> Path:
    run_dir.mkdir(parents=True, exist_ok=True)
    path = run_dir / MANIFEST
    tmp = path.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(manifest, indent=2, default=str) + "\n", encoding="utf-8")
    tmp.replace(path)
    return path

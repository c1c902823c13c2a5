"""Generate proven scenarios: `generate(seed, count, out)` behind `manage.py generate`.

The count is shared evenly among the environments; within one, the families take turns
(round robin), so every family of the hand-written scenarios is represented wherever it exists.
Each turn composes a candidate from its own random stream (`random.Random` seeded with
"seed:environment:family:turn"), its condition time in the next of the window's strata
(apps.generate.arrivals), and proves it; a candidate that fails a proof is discarded and counted
by reason, and the turn tries a quieter one (`_fallbacks`); one that repeats an earlier one's
condition on the same items at the same second is discarded as a duplicate, and a family with
`GIVE_UP` discards and no proven scenario leaves the rotation. Same seed, same templates and
catalog: byte-identical files and manifest.

Output: `<out>/<environment>/<family>-g<seed>-<n>.json` (ordinary scenario files: `bench run`,
`bench validate`, the server and the admin take the folder as `SENTINEL_SCENARIO_DIR` or
`--scenarios`), and `<out>/manifest.json`: each file's family, template, random stream and proof
results, and the discards by reason and by family.
"""

from __future__ import annotations

import hashlib
import json
import random
import re
import shutil
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from apps.generate.arrivals import STRATA
from apps.generate.compose import ASPECTS, Candidate, compose
from apps.generate.proofs import Proof, prove
from apps.generate.templates import Template, item_of, item_pool, read_templates
from apps.scenarios.generated_names import generated_id
from apps.scenarios.serialization import render_json
from events.catalog import load_catalog

MANIFEST = "manifest.json"
GIVE_UP = 12  # discards in a row, with nothing proven, before a family leaves the rotation
TURNS_PER_SCENARIO = 6  # an environment stops after this many turns per scenario asked
MAX_VARIANTS = 50  # the admin's "Generate variants…" at once


class GenerationError(ValueError):
    """Bad input to the generator: the message names the problem."""


@dataclass
class Generated:
    entries: list[dict[str, Any]] = field(default_factory=list)  # the manifest's scenarios
    documents: list[dict[str, Any]] = field(default_factory=list)
    candidates: int = 0
    discarded: Counter = field(default_factory=Counter)  # reason -> count
    discarded_by_family: Counter = field(default_factory=Counter)
    duplicates: int = 0
    abandoned: list[str] = field(default_factory=list)  # families that left the rotation
    # family -> why its template, unvaried, fails the proofs (it is not generated from)
    unprovable: dict[str, str] = field(default_factory=dict)
    templates_hash: str = ""  # sha256 of the templates drawn from, for the manifest


def _reason(proof: Proof) -> str:
    """A discard's reason, numbers masked so alike failures count together."""
    return re.sub(r"-?\d+(\.\d+)?", "N", proof.problems[0])


def trigger_item(document: dict[str, Any]) -> str | None:
    """The catalog item whose arrival makes the condition hold (None for a no-op)."""
    condition = document.get("condition_at")
    if condition is None:
        return None
    at = [e for e in document["events"] if float(e["time"]) == float(condition)]
    item = item_of(at[-1]) if at else None
    return item[1] if item else (at[-1]["type"] if at else None)


def _duplicate_key(document: dict[str, Any], family: str) -> tuple:
    """The same condition on the same items: family (its eval_sql), trigger second, items."""
    items = sorted(json.dumps(e["payload"], sort_keys=True) for e in document["events"])
    condition = document.get("condition_at")
    return (
        document["environment"],
        family,
        None if condition is None else round(float(condition)),
        tuple(items),
    )


def select_templates(
    templates: list[Template], environments: Iterable[str] | None, families: Iterable[str] | None
) -> dict[str, list[Template]]:
    """Templates by environment, narrowed by `--env` and `--families` (names, or the kinds
    `passive`, `active`, `noop`); a name that matches nothing is an error."""
    by_env: dict[str, list[Template]] = {}
    for template in templates:
        by_env.setdefault(template.environment, []).append(template)
    if environments:
        unknown = sorted(set(environments) - set(by_env))
        if unknown:
            raise GenerationError(
                f"--env: no templates for {', '.join(unknown)}; known: {', '.join(sorted(by_env))}"
            )
        by_env = {e: by_env[e] for e in sorted(set(environments))}
    if families:
        wanted = set(families)
        known = {t.family for ts in by_env.values() for t in ts} | {"passive", "active", "noop"}
        unknown = sorted(wanted - known)
        if unknown:
            raise GenerationError(
                f"--families: unknown {', '.join(unknown)}; known: kinds passive, active, noop "
                "or a family name such as "
                + ", ".join(sorted({t.family for ts in by_env.values() for t in ts})[:5])
            )
        by_env = {
            e: [t for t in ts if t.family in wanted or t.kind in wanted] for e, ts in by_env.items()
        }
        by_env = {e: ts for e, ts in by_env.items() if ts}
    return by_env


def _templates_hash(templates: Iterable[Template]) -> str:
    """What the files depend on besides the seed and the catalog: the templates' documents."""
    digest = hashlib.sha256()
    for template in templates:
        digest.update(template.source.encode() + b"\0")
        digest.update(json.dumps(template.document, sort_keys=True).encode() + b"\0")
    return digest.hexdigest()


def _check_aspects(aspects: tuple[str, ...]) -> None:
    unknown = sorted(set(aspects) - set(ASPECTS))
    if unknown or not aspects:
        raise GenerationError(f"vary: choose among {', '.join(ASPECTS)}; got {list(aspects)}")


def _prepare(out: Path, protected: Iterable[Path]) -> None:
    """An empty output folder: new, empty, or a previous generation's (which is replaced)."""
    out = out.resolve()
    for folder in protected:
        folder = Path(folder).resolve()
        if out == folder or folder in out.parents:
            raise GenerationError(f"--out {out} is inside {folder}: write generated files apart")
    if out.exists():
        if not out.is_dir():
            raise GenerationError(f"--out {out} is a file, not a folder")
        contents = list(out.iterdir())
        if contents and not (out / MANIFEST).is_file():
            raise GenerationError(
                f"--out {out} is not empty and holds no {MANIFEST}: choose a new folder"
            )
        for path in contents:
            shutil.rmtree(path) if path.is_dir() else path.unlink()
    out.mkdir(parents=True, exist_ok=True)


def _shares(count: int, environments: list[str]) -> dict[str, int]:
    base, extra = divmod(count, len(environments))
    return {e: base + (1 if i < extra else 0) for i, e in enumerate(environments)}


def generate(
    *,
    seed: int,
    count: int,
    out: Path | None,
    templates_root: Path,
    environments: Iterable[str] | None = None,
    families: Iterable[str] | None = None,
    aspects: tuple[str, ...] = ASPECTS,
    protected: Iterable[Path] = (),
    progress: Callable[[str], None] | None = None,
    prover: Callable[[Candidate], Proof] | None = None,
) -> Generated:
    """Compose, prove and (with `out`) write `count` scenarios; see the module doc."""
    if count < 1:
        raise GenerationError(f"--count must be >= 1, got {count}")
    _check_aspects(aspects)
    templates = read_templates(templates_root)
    by_env = select_templates(templates, environments, families)
    if not by_env:
        raise GenerationError(f"no templates to generate from in {templates_root}")
    prover = prover or (lambda c: prove(c.document, c.proven))
    catalog = load_catalog()
    result = Generated(templates_hash=_templates_hash(t for ts in by_env.values() for t in ts))
    for environment, share in _shares(count, sorted(by_env)).items():
        _generate_environment(
            environment, by_env[environment], share, seed, aspects, catalog, prover, result
        )
        if progress:
            kept = sum(1 for e in result.entries if e["environment"] == environment)
            progress(f"{environment}: {kept} proven")
    if out is not None:
        write(out, seed, aspects, result, protected)
    return result


def _fallbacks(aspects: tuple[str, ...]) -> list[tuple[bool, tuple[str, ...]]]:
    """A turn's tries, each only if the one before fails a proof: a full draw; a quiet one
    (the template's trigger, no added distractors, the background moved with the story: a count
    kept); one that keeps
    the template's times (a value moving between waypoints that the warp would bend)."""
    tries = [(False, aspects), (True, aspects)]
    if "timing" in aspects and len(aspects) > 1:
        tries.append((False, tuple(a for a in aspects if a != "timing")))
    return tries


def _provable(template, seed, catalog, prover, result) -> bool:
    """Whether the family's template itself, unvaried (a withheld family: only withheld),
    passes the proofs; if not, no variant is tried (a count that later items reach anyway
    cannot be withheld into a no-op) and the reason is kept for the manifest."""
    candidate = compose(
        template,
        random.Random(f"{seed}:{template.environment}:{template.family}:as-is"),
        scenario_id=f"{template.environment}-{template.family}",
        catalog=catalog,
        pool={},
        aspects=(),
    )
    proof = prover(candidate)
    if not proof.ok:
        result.unprovable[f"{template.environment}/{template.family}"] = proof.problems[0]
    return proof.ok


def variants(
    template: Template,
    *,
    seed: int,
    count: int,
    aspects: tuple[str, ...] = ASPECTS,
    prover: Callable[[Candidate], Proof] | None = None,
) -> Generated:
    """Up to `count` proven variants of one scenario (the admin's "Generate variants…"), drawn
    as `generate` draws its family's: same streams, same proofs, same discards."""
    if not 1 <= count <= MAX_VARIANTS:
        raise GenerationError(f"how many: between 1 and {MAX_VARIANTS}, got {count}")
    _check_aspects(aspects)
    result = Generated()
    prover = prover or (lambda c: prove(c.document, c.proven))
    _generate_environment(
        template.environment, [template], count, seed, aspects, load_catalog(), prover, result
    )
    return result


def _generate_environment(environment, templates, share, seed, aspects, catalog, prover, result):
    rotation = [t for t in templates if _provable(t, seed, catalog, prover, result)]
    pools = {t.family: item_pool(t, catalog) for t in templates}
    proven = Counter()
    failures = Counter()
    seen: set[tuple] = set()
    # The order in which the environment's scenarios take the window's strata, one after the
    # other: with the families in turn, every family and every stratum gets its share.
    strata = list(range(STRATA))
    random.Random(f"{seed}:{environment}:strata").shuffle(strata)
    kept = turn = 0
    while kept < share and rotation and turn < share * TURNS_PER_SCENARIO:
        template = rotation[turn % len(rotation)]
        stream = f"{seed}:{environment}:{template.family}:{turn}"
        turn += 1
        number = proven[template.family] + 1
        scenario_id = generated_id(environment, template.family, seed, number)
        rng = random.Random(stream)
        for quiet, varied in _fallbacks(aspects):
            candidate = compose(
                template,
                rng,
                scenario_id=scenario_id,
                catalog=catalog,
                pool=pools[template.family],
                aspects=varied,
                note=f"Generated from {template.source} (family {template.family}, seed {seed}).",
                quiet=quiet,
                stratum=strata[kept % STRATA],
            )
            result.candidates += 1
            key = _duplicate_key(candidate.document, template.family)
            if key in seen:
                result.duplicates += 1
                proof = None
                break
            proof = prover(candidate)
            if proof.ok:
                break
            result.discarded[_reason(proof)] += 1
            result.discarded_by_family[f"{environment}/{template.family}"] += 1
        if proof is None:
            continue
        if not proof.ok:
            failures[template.family] += 1
            if failures[template.family] >= GIVE_UP and not proven[template.family]:
                rotation.remove(template)
                result.abandoned.append(f"{environment}/{template.family}")
            continue
        seen.add(key)
        proven[template.family] += 1
        kept += 1
        result.documents.append(candidate.document)
        result.entries.append(
            {
                "file": f"{environment}/{template.family}-g{seed}-{number:04d}.json",
                "id": scenario_id,
                "environment": environment,
                "family": template.family,
                "kind": template.kind,
                "milestone": template.milestone,
                "template": template.source,
                "stream": stream,
                "aspects": list(candidate.aspects),
                "condition_at": candidate.document.get("condition_at"),
                "trigger_item": trigger_item(candidate.document),
                "distractors_added": list(candidate.added),
                "proofs": {"verdicts": proof.verdicts, "watched_page": proof.watch},
            }
        )


def write(out: Path, seed: int, aspects, result: Generated, protected: Iterable[Path]) -> None:
    _prepare(out, protected)
    for entry, document in zip(result.entries, result.documents, strict=True):
        path = out / entry["file"]
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(render_json(document), encoding="utf-8")
    manifest = {
        "seed": seed,
        "aspects": list(aspects),
        "catalog_hash": load_catalog().content_hash,
        "templates_hash": result.templates_hash,
        "written": len(result.entries),
        "candidates": result.candidates,
        "discarded": sum(result.discarded.values()),
        "duplicates": result.duplicates,
        "discarded_by_reason": dict(sorted(result.discarded.items())),
        "discarded_by_family": dict(sorted(result.discarded_by_family.items())),
        "abandoned_families": result.abandoned,
        "unprovable_families": dict(sorted(result.unprovable.items())),
        "scenarios": result.entries,
    }
    (out / MANIFEST).write_text(render_json(manifest), encoding="utf-8")

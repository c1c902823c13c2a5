"""`manage.py generate`: proven scenarios from our hand-written ones, reproducible from a seed.

Every test generates into its own temporary folder from the session's copy of our scenarios;
nothing is written into the repository's scenarios/ or fixtures/.
"""

from __future__ import annotations

import io
import json
import re
import shlex
from pathlib import Path

import pytest
from django.core.management import CommandError, call_command

from apps.generate.generate import MANIFEST
from tests.conftest import OUR_SCENARIOS
from tests.first_hour.test_readme_harness import code_blocks, readme_section

pytestmark = pytest.mark.django_db


def generate(out: Path, *args: str, templates: Path = OUR_SCENARIOS) -> list[str]:
    stdout = io.StringIO()
    call_command("generate", "--out", str(out), "--templates", str(templates), *args, stdout=stdout)
    return stdout.getvalue().splitlines()


def contents(folder: Path) -> dict[str, bytes]:
    return {
        p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*.json"))
    }


def test_the_same_seed_writes_the_same_bytes_and_another_seed_other_files(tmp_path):
    args = ("--count", "6", "--env", "micromail")
    generate(tmp_path / "a", "--seed", "3", *args)
    generate(tmp_path / "b", "--seed", "3", *args)
    generate(tmp_path / "c", "--seed", "4", *args)
    first, again, other = (contents(tmp_path / name) for name in "abc")
    assert len(first) == 7  # six scenarios and the manifest
    assert first == again
    scenarios = {k: v for k, v in first.items() if k != MANIFEST}
    assert not set(scenarios.values()) & set(other.values())


def test_the_command_prints_the_diversity_figures_and_the_manifest_says_why(tmp_path):
    lines = generate(tmp_path, "--seed", "7", "--count", "12", "--env", "micromail", "--env",
                     "microhood")  # fmt: skip
    text = "\n".join(lines)
    assert re.search(r"^distinct prompts: \d+; distinct trigger items: \d+$", text, re.M)
    assert re.search(r"^generated: 12 scenarios, \d+ targeted, no-ops \d+ \(", text, re.M)
    assert "condition_at per 100 s bin: [  0, 100) s" in text
    assert "condition_at spread: ok: no bin above 25 %" in text  # a sample: not judged
    assert re.search(r"^generate: seed=7 written=12 candidates=\d+ .* wall_s=", lines[-1])
    manifest = json.loads((tmp_path / MANIFEST).read_text())
    assert manifest["written"] == 12
    assert {e["environment"] for e in manifest["scenarios"]} == {"micromail", "microhood"}
    for entry in manifest["scenarios"]:
        assert (tmp_path / entry["file"]).is_file()
        assert entry["proofs"]["verdicts"]["oracle"] is True
        assert entry["proofs"]["verdicts"]["early"] is False
        assert entry["proofs"]["verdicts"]["never"] is (entry["kind"] == "noop")
        assert entry["family"] in entry["id"] and entry["template"].endswith(".json")
    # Every candidate is written, discarded by a proof or discarded as a duplicate.
    assert manifest["candidates"] == 12 + manifest["discarded"] + manifest["duplicates"]


def test_a_family_whose_distractors_satisfy_the_condition_has_them_discarded_not_written(
    tmp_path,
):
    """A family whose condition any other mail meets: every candidate with a distractor
    arriving before its trigger fails the proofs (the condition holds early), is counted, and
    is not written; what is written has no such distractor."""
    source = json.loads((OUR_SCENARIOS / "micromail" / "sender-absolute-passive.json").read_text())
    trigger = "base-77"
    known = sorted(
        {e["payload"]["email_id"] for e in source["events"][1:]} - {trigger}
        | set(source["events"][0]["payload"]["email_ids"])
    )
    listed = ", ".join(f"'{i}'" for i in known)
    # "Any mail I have not seen yet": the trigger, but also any distractor brought in.
    source["eval_sql"] = f"SELECT EXISTS (SELECT 1 FROM emails WHERE id NOT IN ({listed}))"
    source["annotator_notes"] = f"Known mail: {', '.join(known)}."
    source["id"] = "micromail-any-new-absolute-passive"
    templates = tmp_path / "templates"
    (templates / "micromail").mkdir(parents=True)
    (templates / "micromail" / "any-new-absolute-passive.json").write_text(json.dumps(source))

    out = tmp_path / "out"
    generate(out, "--seed", "5", "--count", "8", "--families", "any-new-absolute-passive",
             templates=templates)  # fmt: skip

    manifest = json.loads((out / MANIFEST).read_text())
    early = [r for r in manifest["discarded_by_reason"] if "before condition_at" in r]
    assert early and manifest["discarded_by_reason"][early[0]] >= 1
    assert manifest["discarded_by_family"]["micromail/any-new-absolute-passive"] >= 1
    written = [json.loads((out / e["file"]).read_text()) for e in manifest["scenarios"]]
    assert written  # the quiet fallback (no distractors) proves
    for scenario in written:
        before = [
            e["payload"]["email_id"]
            for e in scenario["events"][1:]
            if e["time"] < scenario["condition_at"]
        ]
        assert set(before) <= set(known), before


def test_bad_input_is_refused_with_a_message_naming_it(tmp_path):
    with pytest.raises(CommandError, match="--families: unknown no-such-family"):
        generate(tmp_path / "a", "--seed", "1", "--count", "1", "--families", "no-such-family")
    with pytest.raises(CommandError, match="--env: no templates for microspace"):
        generate(tmp_path / "a", "--seed", "1", "--count", "1", "--env", "microspace")
    with pytest.raises(CommandError, match="is inside"):
        generate(OUR_SCENARIOS / "generated", "--seed", "1", "--count", "1", "--env", "micromail")
    (tmp_path / "busy").mkdir()
    (tmp_path / "busy" / "notes.txt").write_text("mine")
    with pytest.raises(CommandError, match=r"not empty and holds no manifest\.json"):
        generate(tmp_path / "busy", "--seed", "1", "--count", "1", "--env", "micromail")
    assert (tmp_path / "busy" / "notes.txt").read_text() == "mine"


@pytest.mark.e2e
@pytest.mark.django_db(transaction=True)
def test_the_readme_example_generates_a_folder_that_bench_validate_passes(tmp_path):
    """The README's two commands as written (the folder under this test's own): every
    generated scenario passes the control agents through the real harness and server."""
    (code,) = [
        c for lang, c, _ in code_blocks(readme_section("Generating tasks")) if lang == "bash"
    ]
    outputs = []
    for line in filter(None, code.splitlines()):
        argv = shlex.split(line)
        assert argv[:2] == [".venv/bin/python", "manage.py"], line
        args = [str(tmp_path / a) if a.startswith("generated/") else a for a in argv[2:]]
        out = io.StringIO()
        call_command(*args, stdout=out)
        outputs.append(out.getvalue().splitlines())
    generated, validated = outputs
    manifest = json.loads((tmp_path / "generated" / "small" / MANIFEST).read_text())
    total = manifest["written"]
    targeted = sum(1 for e in manifest["scenarios"] if e["kind"] != "noop")
    assert generated[-1].startswith(f"generate: seed=7 written={total} ")
    assert not [line for line in validated if line.startswith("PROBLEM")], validated
    summary = validated[-1]
    assert f"scenarios={total} oracle={total}/{total} " in summary, summary
    assert f"early_fail={targeted}/{targeted} never_ok={total}/{total} " in summary, summary
    assert f"act_all_timely=0/{targeted} " in summary and f"quitter=0/{total} " in summary
    assert f"unseen=0/{targeted} " in summary, summary


def test_bench_refuses_a_scenario_folder_that_is_not_there(tmp_path):
    for subcommand in (["run", "nightly", "--agent", "oracle"], ["validate"]):
        with pytest.raises(CommandError, match=r"--scenarios .*missing: no such folder"):
            call_command("bench", *subcommand, "--scenarios", str(tmp_path / "missing"))


def test_an_ephemeral_family_keeps_its_window_around_the_trigger_it_delivers(tmp_path):
    """The trigger moved (and swapped for a kin item): what takes it away again moves and
    follows it, and `condition_until` says when that now is."""
    templates = tmp_path / "templates"
    for source in ("microchat/unsent-build-ephemeral-active.json",
                   "microdin/backend-fit-ephemeral-subjective-absolute-active.json"):  # fmt: skip
        (templates / source).parent.mkdir(parents=True, exist_ok=True)
        (templates / source).write_text((OUR_SCENARIOS / source).read_text())
    generate(tmp_path / "out", "--seed", "5", "--count", "6", templates=templates)
    written = [json.loads(p.read_text()) for p in sorted((tmp_path / "out").glob("*/*.json"))]
    assert written
    for scenario in written:
        events = scenario["events"]
        (trigger,) = [e for e in events if e["time"] == scenario["condition_at"]]
        item = next(iter(trigger["payload"].values()))
        taken = [e for e in events if e["time"] > trigger["time"] and item in e["payload"].values()]
        assert [e["time"] for e in taken] == [scenario["condition_until"]], scenario["id"]

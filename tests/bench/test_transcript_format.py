"""The README's transcript line (section "The task timeline") is what the harness reads."""

from __future__ import annotations

from apps.bench.transcripts import Step, read_transcript
from tests.first_hour.test_readme_harness import code_blocks, readme_section


def test_the_documented_transcript_line_reads_as_a_step_on_the_runs_clock(tmp_path):
    (line,) = [
        code for lang, code, _ in code_blocks(readme_section("The task timeline")) if lang == "json"
    ]
    (tmp_path / "transcript.jsonl").write_text(line)
    (step,) = read_transcript(tmp_path / "transcript.jsonl")
    assert isinstance(step, Step)
    assert (step.number, step.sim_start, step.sim_time, step.tool) == (2, 31.5, 35.02, "wait_for")
    (check,) = step.checks
    assert check["met"] is True and check["sim_time"] <= step.sim_time

"""The README's transcript line (section "The task timeline") is what the harness reads."""

from __future__ import annotations

from apps.bench.transcripts import Step, read_transcript, render_transcript_page
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


def test_the_transcript_page_shows_the_diff_the_model_was_given(tmp_path):
    (line,) = [
        code for lang, code, _ in code_blocks(readme_section("The task timeline")) if lang == "json"
    ]
    (tmp_path / "transcript.jsonl").write_text(line)
    page = render_transcript_page(
        title="t", facts=[], task_folder=tmp_path, page_folder=tmp_path, back_href="r.html"
    )
    assert "sim 35.0 s" in page and "wait_for asked the model 1 time<" in page
    assert "sim 34.9 s: met — a new change mentions" in page
    assert "<pre>+ Kevin Lee  Expense reports …</pre>" in page

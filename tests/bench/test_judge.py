"""The agent's report judged against its scenario's `contact_rubric`: by a model with
`bench grade --judge` (here the scripted model server, a real HTTP server, plays the judge), or
by the rubric's keywords without one. A vague "done" is an incorrect report, a specific one a
correct report, and the grade reports success with a correct report beside success."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError

from apps.bench.judge import JUDGEMENT, JudgeError, by_keywords, judge_prompt, read_answer
from apps.browser_agent.scripted_model import parse_script, scripted_model_server
from apps.scenarios.format import ScenarioError, parse_scenario
from apps.scenarios.library import get_scenario
from tests.conftest import OUR_SCENARIOS, ours

RUBRIC = {
    "rubric": "Names the sender, Kevin Lee, and what he asked for (the expense report).",
    "must_mention": ["Kevin Lee", "expense"],
}
VAGUE = "Done."
SPECIFIC = "Kevin Lee just emailed: the expense reports window closes early, on Friday."


def write_results(root: Path) -> Path:
    """Three passed tasks with a rubric (a vague and a specific report, and a specific one that
    failed) and one without a rubric."""
    reports = {"vague": (VAGUE, True), "specific": (SPECIFIC, True), "late": (SPECIFIC, False)}
    for name, (message, success) in {**reports, "plain": ("ok", True)}.items():
        folder = root / "judged" / "micromail" / name
        folder.mkdir(parents=True)
        result = {
            "success": success,
            "detail": "",
            "evaluation_time": 20.0,
            "condition_at": 10.0,
            "contact_get_time": None,
            "contact_post_time": 12.0,
            "contact_message": message,
            "category": "passive-absolute",
            "prompt": "Tell me when Kevin Lee writes about expenses.",
        }
        if name != "plain":
            result["contact_rubric"] = RUBRIC
        (folder / "results.json").write_text(json.dumps(result))
    return root


def grade(root: Path, *options: str) -> str:
    out = io.StringIO()
    call_command("bench", "grade", "judged", "--results-dir", str(root), *options, stdout=out)
    return out.getvalue()


def judgement_of(root: Path, name: str) -> dict:
    return json.loads((root / "judged" / "micromail" / name / JUDGEMENT).read_text())


def test_the_keyword_rule_fails_a_vague_report_and_passes_a_specific_one():
    assert not by_keywords(RUBRIC, VAGUE).correct
    assert "'Kevin Lee'" in by_keywords(RUBRIC, VAGUE).why
    assert by_keywords(RUBRIC, SPECIFIC).correct
    assert by_keywords(RUBRIC, "KEVIN   lee: EXPENSE").correct  # case and spacing


def test_without_a_model_grade_judges_by_keywords(tmp_path):
    text = grade(write_results(tmp_path))
    assert "Reports judged correct (keywords): 66.7% (2/3)" in text
    assert "Success with a correct report (tasks with a contact rubric): 33.3% (1/3)" in text
    assert judgement_of(tmp_path, "vague")["correct"] is False
    assert judgement_of(tmp_path, "specific") == {
        "correct": True,
        "why": "mentions all",
        "by": "keywords",
        "prompt": "",
        "answer": "",
    }
    assert not (tmp_path / "judged" / "micromail" / "plain" / JUDGEMENT).exists()


def test_a_judge_model_marks_the_vague_report_incorrect_and_keeps_its_prompt(tmp_path):
    script = parse_script(
        {"model": "judge-1", "agent": [{"call": "noop"}], "judge": {"yes_when_any": ["Kevin"]}}
    )
    root = write_results(tmp_path)
    with scripted_model_server(script) as server:
        text = grade(root, "--judge", "judge-1", "--judge-url", server.base_url)
    assert "Reports judged correct (judge-1): 66.7% (2/3)" in text
    vague, specific = judgement_of(root, "vague"), judgement_of(root, "specific")
    assert (vague["correct"], specific["correct"]) == (False, True)
    assert vague["by"] == "judge-1" and vague["prompt"].endswith("=== report ===\nDone.")
    assert RUBRIC["rubric"] in vague["prompt"]  # the rubric is what the model judges by
    assert '"met": false' in vague["answer"]


def test_the_html_report_shows_each_report_and_whether_it_is_correct(tmp_path):
    root = write_results(tmp_path)
    grade(root, "--html", str(tmp_path / "report.html"))
    html = (tmp_path / "report.html").read_text()
    section = html.split("<h2>Reports of judged (judged by keywords)</h2>")[1].split("<h2>")[0]
    assert "Success with a correct report (tasks with a contact rubric): 33.3% (1/3)" in section
    assert (
        "<td>Done.</td><td>does not mention &#x27;Kevin Lee&#x27;, &#x27;expense&#x27;" in section
    )
    assert section.count("<td>correct</td>") == 2 and "micromail/plain" not in section


def test_a_judge_that_cannot_be_reached_is_an_error_not_a_figure(tmp_path):
    root = write_results(tmp_path)
    with pytest.raises(CommandError, match="judge model 'judge-1' could not be asked"):
        grade(root, "--judge", "judge-1", "--judge-url", "http://127.0.0.1:9/v1")


def test_answers_are_read_as_json_or_yes_no():
    assert read_answer('{"correct": true, "why": "names him"}') == (True, "names him")
    assert read_answer('Sure. {"met": false, "why": "vague"}')[0] is False
    assert read_answer("No: it does not name the sender")[0] is False
    with pytest.raises(JudgeError, match="neither JSON"):
        read_answer("maybe")
    assert "=== report ===\nhi" in judge_prompt("watch", RUBRIC, "hi")


@pytest.mark.parametrize(
    ("rubric", "problem"),
    [
        ("say who", "contact_rubric: must be an object"),
        ({"must_mention": ["", "x"]}, "contact_rubric.must_mention: must be a list"),
        ({"rubric": " "}, "needs a rubric text or must_mention"),
        ({"keywords": ["x"]}, r"unknown keys \['keywords'\]"),
    ],
)
def test_a_bad_rubric_is_refused_naming_the_field(rubric, problem):
    data = {
        **get_scenario("micromail-inbox-relative-passive").to_run_spec(),
        "contact_rubric": rubric,
    }
    with pytest.raises(ScenarioError, match=problem):
        parse_scenario(data)


@pytest.mark.parametrize(
    ("scenario_id", "specific"),
    [
        ("microgram-first-story-whose-ephemeral-active", "It was Femi's story (fadeyemi)."),
        (
            "microfy-run-song-subjective-absolute-active",
            "Added Thunder Run by Odd Meridian to Gym Rotation.",
        ),
    ],
)
def test_our_judged_scenarios_tell_a_vague_report_from_a_specific_one(scenario_id, specific):
    (scenario,) = [s for s in ours() if s.id == scenario_id]
    assert not by_keywords(scenario.contact_rubric, VAGUE).correct
    assert by_keywords(scenario.contact_rubric, specific).correct


# Our scenarios' rubrics: the report a careful agent writes is correct; "done", and a report
# naming the closest distractor instead, are not.
OUR_REPORTS = {
    "microlendar/family-clash-ephemeral-subjective-absolute-passive.json": (
        "The Larkspur Logistics partner dinner (Fri Sep 26, 6:30pm) clashes with Lily's school play.",
        "The late release check on Wednesday clashes with your haircut.",
    ),
    "microdin/fits-priya-subjective-absolute-passive.json": (
        "For Priya: Quillfeather Software posted a remote Frontend Engineer role (React, TypeScript).",
        "For Priya: Harborview Health posted a Web Platform Engineer role (React, WCAG).",
    ),
    "microhub/sign-in-review-ephemeral-subjective-absolute-active.json": (
        "Held 'feat: TOTP enrolment and verification' by tmansour for security review.",
        "Held 'docs: webhook retries and replays' by hquinn for security review.",
    ),
}


@pytest.mark.parametrize("path", sorted(OUR_REPORTS))
def test_our_rubrics_pass_the_specific_report_and_fail_a_vague_or_mistaken_one(path):
    rubric = json.loads((OUR_SCENARIOS / path).read_text())["contact_rubric"]
    specific, mistaken = OUR_REPORTS[path]
    assert by_keywords(rubric, specific).correct
    assert not by_keywords(rubric, VAGUE).correct
    assert not by_keywords(rubric, mistaken).correct

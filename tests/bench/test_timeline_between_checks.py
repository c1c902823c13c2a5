"""The timeline tells "the model was asked and said no" from "the change had not reached it".

A fixed cast, no server: the self user waits for Kevin Lee's email. wait_for's judge is asked
at 31 s about a distractor (no), Kevin's email (the trigger) fires at 60 s while wait_for is
between questions, and the next question, at 75 s, shows the model his email's diff block
(yes); the agent contacts at 78 s. The timeline puts the trigger before that question, and the
question's row holds the diff the model was given.
"""

from __future__ import annotations

import json
import re

from apps.bench.task_trace import LogEntry, TaskTrace
from apps.bench.timeline import Links, build_timeline, render_timeline
from apps.bench.transcripts import read_transcript

ROOT = "/r/tok/micromail"
KEVIN_BLOCK = "+ Kevin Lee  Expense reports: submission window closes early  just now"
DISTRACTOR_BLOCK = "+ Priya Shah  Travel policy update  just now"
SCENARIO = {
    "id": "kevin",
    "condition_at": 60.0,
    "kill_at": 200.0,
    "eval_sql": "SELECT 1",
    "events": [],
}
LOG = [
    LogEntry(1, 0.0, "scenario", "preload_emails", {"email_ids": ["base-01"]}, 0),
    LogEntry(2, 0.5, "lifecycle", "start", {}),
    LogEntry(3, 0.6, "view", "page", {"path": f"{ROOT}/?folder=inbox"}),
    LogEntry(4, 30.0, "scenario", "new_email", {"email_id": "base-36"}, 1),
    LogEntry(5, 60.0, "scenario", "new_email", {"email_id": "base-77"}, 2),
    LogEntry(6, 78.0, "lifecycle", "contact_post", {"message": "Kevin wrote"}),
]
STEPS = [
    {"step": 1, "sim_start": 2.0, "sim_time": 76.0, "url": f"http://h{ROOT}/?folder=inbox",
     "tool": "wait_for", "arguments": {"condition": "an email from Kevin Lee", "timeout": 200},
     "result": "met: true", "screenshot": "transcript/step-001.jpg",
     "usage": {"input_tokens": 900, "output_tokens": 30},
     "checks": [
         {"sim_time": 31.0, "blocks": [DISTRACTOR_BLOCK], "met": False, "why": "not Kevin",
          "usage": {"input_tokens": 200, "output_tokens": 9}},
         {"sim_time": 75.0, "blocks": [KEVIN_BLOCK], "met": True, "why": "Kevin wrote",
          "usage": {"input_tokens": 210, "output_tokens": 9}},
     ]},
    {"step": 2, "sim_start": 76.5, "sim_time": 78.4, "url": f"http://h{ROOT}/?folder=inbox",
     "tool": "contact", "arguments": {"message": "Kevin wrote"}, "result": "contacted",
     "screenshot": "transcript/step-002.jpg", "usage": {"input_tokens": 950, "output_tokens": 20}},
]  # fmt: skip


def timeline(tmp_path):
    (tmp_path / "transcript.jsonl").write_text("\n".join(json.dumps(s) for s in STEPS))
    trace = TaskTrace(
        scenario=SCENARIO,
        log=LOG,
        steps=read_transcript(tmp_path / "transcript.jsonl"),
        result={"success": True, "detail": "eval_sql returned 1", "reaction_time": 9.0},
        prompt="Tell me when Kevin Lee writes.",
        run={"speed_factor": 2.0},
    )
    return build_timeline(trace, title="kevin", environment_root=ROOT, window=30.0)


def test_the_trigger_comes_between_the_question_that_missed_it_and_the_one_that_saw_it(tmp_path):
    entries = timeline(tmp_path).entries
    kinds = [e.kind for e in entries]
    first_question, next_question = (n for n, kind in enumerate(kinds) if kind == "check")
    trigger = kinds.index("trigger")
    assert first_question < trigger < next_question < kinds.index("contact")
    assert entries[first_question].blocks == (DISTRACTOR_BLOCK,)
    assert entries[next_question].blocks == (KEVIN_BLOCK,)
    # "The site at this moment" of the question after the trigger: a log position that has it.
    assert entries[next_question].seq == 5 and entries[next_question].page == "?folder=inbox"


def test_the_page_shows_the_diff_the_model_was_given_under_its_question(tmp_path):
    links = Links(site_at=lambda seq, page: f"/at/{seq}/{page}", screenshot=lambda n: f"/f/{n}")
    html = render_timeline(timeline(tmp_path), links)
    rows = re.findall(r'<li id="tl-\d+" class="kind-(\w+)".*?</li>', html, re.S)
    assert rows.index("trigger") < rows.index("check", rows.index("trigger"))
    question = re.search(
        r'<li id="tl-\d+" class="kind-check" data-at="75.000">.*?</li>', html, re.S
    )
    assert question and "Kevin Lee  Expense reports" in question.group(0)
    assert "its answer: Kevin wrote" in question.group(0)
    assert 'href="/at/5/?folder=inbox"' in question.group(0)
    assert "reaction window" in html and "condition_at" in html


def test_a_flooded_log_shows_its_first_moments_and_says_how_many_more():
    views = [LogEntry(n, n * 0.01, "view", "page", {"path": f"{ROOT}/"}) for n in range(1, 2501)]
    trace = TaskTrace(scenario=SCENARIO, log=views, steps=[], result={}, prompt=None)
    built = build_timeline(trace, title="flood", environment_root=ROOT, window=30.0)
    links = Links(site_at=lambda seq, page: f"/at/{seq}", screenshot=lambda n: n)
    html = render_timeline(built, links)
    assert html.count('<li id="tl-') == 2000 and html.count('class="mark kind-view"') == 2000
    assert "500 later moments not shown" in html

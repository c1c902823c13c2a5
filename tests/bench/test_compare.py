"""`bench grade A B`: two agents' result trees (written by hand) compared side by side.

The cast: *prompt* reacts within seconds of each condition; *sleeper* contacts just before the
deadline, as the control agent of that name does — it passes the passive tasks late, fails
what needs an action in time and the no-op it should have left alone.
"""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError

REPO = Path(__file__).resolve().parents[2]
SLEEPER_CONTACT = 177.5  # deadline 182.5 s (600 / 4 + 30) minus 5
TASKS = {
    # task: (category, condition_at)
    "passive-abs": ("passive-absolute", 60.0),
    "passive-rel": ("passive-relative", 100.0),
    "active-abs": ("active-absolute", 80.0),
    "active-rel": ("active-relative", 120.0),
    "noop": ("noop", None),
}
RUNS = {
    # agent: {task: (success, contact_get_time, (input tokens, output tokens, tool calls, model))}
    "prompt": {
        "passive-abs": (True, 65.0, (100_000, 2_000, 4, "m")),
        "passive-rel": (True, 108.0, (200_000, 4_000, 6, "m")),
        "active-abs": (True, 90.0, (300_000, 6_000, 8, "m")),
        "active-rel": (False, 100.0, (400_000, 8_000, 10, "m")),  # contacted too early
        "noop": (True, None, (40_000, 800, 2, "m")),
    },
    "sleeper": {
        "passive-abs": (True, SLEEPER_CONTACT, (10_000, 100, 1, "m")),
        "passive-rel": (True, SLEEPER_CONTACT, (10_000, 100, 1, "m")),
        "active-abs": (False, SLEEPER_CONTACT, (10_000, 100, 1, "m")),
        "active-rel": (False, SLEEPER_CONTACT, (10_000, 100, 1, "m")),
        "noop": (False, SLEEPER_CONTACT, (10_000, 100, 1, "unpriced-model")),
    },
}


@pytest.fixture
def two_agents(tmp_path) -> Path:
    for agent, runs in RUNS.items():
        for task, (success, contact, (tokens_in, tokens_out, tools, model)) in runs.items():
            category, condition = TASKS[task]
            folder = tmp_path / "results" / agent / "micromail" / task
            folder.mkdir(parents=True)
            result = {
                "success": success,
                "detail": "",
                "evaluation_time": contact or 182.5,
                "condition_at": condition,
                "contact_get_time": contact,
                "contact_post_time": contact,
                "category": category,
                "speed_factor": 4.0,
            }
            (folder / "results.json").write_text(json.dumps(result))
            costs = {
                "input_tokens": tokens_in,
                "output_tokens": tokens_out,
                "tool_calls": tools,
                "model": model,
            }
            (folder / "costs.json").write_text(json.dumps(costs))
    (tmp_path / "eval_config.yaml").write_text(
        "agent_subprocess: [echo]\nprices: {m: {input: 1.25, output: 10}}\n"
    )
    return tmp_path


def grade(root: Path, *args: str) -> str:
    out = io.StringIO()
    call_command(
        "bench",
        "grade",
        *args,
        "--results-dir",
        str(root / "results"),
        "--config",
        str(root / "eval_config.yaml"),
        stdout=out,
    )
    return out.getvalue()


def table_rows(text: str, title: str) -> dict[str, list[str]]:
    """The rows of one console table, by result set: the cells after the name."""
    lines = text.split(title, 1)[1].splitlines()[1:]
    rows = {}
    for line in lines[2:]:  # below the header and its rule
        if not line.strip():
            break
        name, *cells = [c.strip() for c in line.split(" | ")]
        rows[name] = cells
    return rows


def test_success_and_timely_success_by_category_side_by_side(two_agents):
    rows = table_rows(grade(two_agents, "prompt", "sleeper"), "Success by category")
    # tasks, success, timely, no-op, passive, active, absolute, relative
    assert rows["prompt"] == [
        "5",
        "80.0% (4/5)",
        "75.0% (3/4)",  # timely: the targeted tasks only
        "100.0% (1/1)",
        "100.0% (2/2)",
        "50.0% (1/2)",
        "100.0% (2/2)",
        "50.0% (1/2)",
    ]
    assert rows["sleeper"] == [
        "5",
        "40.0% (2/5)",
        "0.0% (0/4)",
        "0.0% (0/1)",
        "100.0% (2/2)",
        "0.0% (0/2)",
        "50.0% (1/2)",
        "50.0% (1/2)",
    ]


def test_a_late_contact_is_a_success_but_not_a_timely_one(two_agents):
    text = grade(two_agents, "sleeper", "prompt")
    timely = table_rows(text, "Timely success by category")
    # timely, passive, active, absolute, relative: no no-op, which has nothing to be timely for
    assert timely["sleeper"] == [
        "0.0% (0/4)",
        "0.0% (0/2)",
        "0.0% (0/2)",
        "0.0% (0/2)",
        "0.0% (0/2)",
    ]
    assert timely["prompt"][:3] == ["75.0% (3/4)", "100.0% (2/2)", "50.0% (1/2)"]
    # A window wide enough for one of the sleeper's reactions (77.5 s; the other is 117.5 s).
    wider = table_rows(grade(two_agents, "sleeper", "prompt", "--timely-window", "100"), "Success")
    assert wider["sleeper"][1:3] == ["40.0% (2/5)", "25.0% (1/4)"]


def test_the_config_reaction_window_is_the_default_timely_window(two_agents):
    config = two_agents / "eval_config.yaml"
    config.write_text(config.read_text() + "reaction_window: 120\n")
    rows = table_rows(grade(two_agents, "prompt", "sleeper"), "Success by category")
    assert rows["sleeper"][1:3] == ["40.0% (2/5)", "50.0% (2/4)"]


def test_cost_tool_calls_and_reaction_time_per_result_set(two_agents):
    text = grade(two_agents, "prompt", "sleeper")
    cost = table_rows(text, "Cost per task (USD")
    # n, mean, median, q1, q3, min, max, unpriced.  prompt: 0.058 0.145 0.29 0.435 0.58
    assert cost["prompt"] == [
        "5",
        "$0.3016",
        "$0.2900",
        "$0.1450",
        "$0.4350",
        "$0.0580",
        "$0.5800",
        "0",
    ]
    # 10k × 1.25 + 100 × 10 per 1M = $0.0135; the no-op's model has no price.
    assert cost["sleeper"][:3] == ["4", "$0.0135", "$0.0135"] and cost["sleeper"][-1] == "1"
    assert "No price in the config for model(s): unpriced-model" in text
    tools = table_rows(text, "Tool calls per task")
    assert tools["prompt"] == ["5", "6.0", "6.0", "4.0", "8.0", "2.0", "10.0"]
    assert tools["sleeper"][:3] == ["5", "1.0", "1.0"]
    reaction = table_rows(text, "Reaction time")
    assert reaction["prompt"] == ["3", "7.7s", "8.0s"]  # 5, 8, 10
    assert reaction["sleeper"] == ["2", "97.5s", "97.5s"]  # 117.5, 77.5


def test_the_comparison_csv_has_one_row_per_result_set(two_agents):
    import csv

    rows = list(csv.DictReader(io.StringIO(grade(two_agents, "prompt", "sleeper", "--csv"))))
    assert [r["result_set"] for r in rows] == ["prompt", "sleeper"]
    sleeper = rows[1]
    assert sleeper["success_rate"] == "0.4000" and sleeper["timely_success_rate"] == "0.0000"
    assert sleeper["timely_passive"] == "0.0000" and sleeper["success_passive"] == "1.0000"
    assert rows[0]["cost_usd_median"] == "0.2900" and rows[0]["tool_calls_mean"] == "6.0000"
    assert rows[0]["reaction_median_s"] == "8.0" and sleeper["unpriced_tasks"] == "1"
    # The paper's future-work axes: these tasks say none, so all are persistent and objective.
    assert sleeper["success_persistent"] == sleeper["success_objective"] == "0.4000"
    assert sleeper["timely_persistent"] == "0.0000"
    assert sleeper["success_ephemeral"] == sleeper["timely_subjective"] == ""  # no such task


def test_one_name_keeps_the_single_set_table(two_agents):
    text = grade(two_agents, "sleeper")
    assert text.startswith("name ") and "Task Success Rate: 40.0% (2/5)" in text
    assert "Comparing" not in text and "Differences beyond the noise" not in text


@pytest.mark.parametrize(
    ("names", "message"),
    [
        (
            ["prompt", "nope"],
            "results folder not found: {root}/results/nope "
            "(result sets in {root}/results: prompt, sleeper)",
        ),
        (["prompt", "prompt"], "result set named twice: prompt"),
    ],
)
def test_a_bad_name_is_one_line_and_exit_2(two_agents, names, message):
    with pytest.raises(CommandError) as failure:
        grade(two_agents, *names)
    assert str(failure.value) == message.format(root=two_agents)
    assert failure.value.returncode == 2


def test_a_bad_timely_window_is_one_line_and_exit_2(two_agents):
    with pytest.raises(
        CommandError, match=r"^--timely-window must be a positive number"
    ) as failure:
        grade(two_agents, "prompt", "sleeper", "--timely-window", "0")
    assert failure.value.returncode == 2


def test_manage_py_exits_2_with_one_line_for_an_unknown_name(two_agents):
    done = subprocess.run(
        [
            *(sys.executable, "manage.py", "bench", "grade", "prompt", "nope"),
            "--results-dir",
            str(two_agents / "results"),
        ],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        f"CommandError: results folder not found: {two_agents}/results/nope "
        f"(result sets in {two_agents}/results: prompt, sleeper)"
    ]


def write_transcript(task_folder: Path, screenshot: bytes) -> None:
    """Two good steps, a line cut off mid-write, a jump in step numbers, a lost screenshot."""
    (task_folder / "transcript").mkdir()
    (task_folder / "transcript" / "step-002.jpg").write_bytes(screenshot)
    (task_folder / "prompt.txt").write_text("Tell me when Alice writes about the budget.")
    steps = [
        {
            "step": 1,
            "t": 0.4,
            "url": None,
            "text": "I will open the inbox.",
            "tool": "visit_url",
            "arguments": {"url": "http://127.0.0.1/r/x/"},
            "result": "ok",
            "screenshot": None,
            "usage": {"input_tokens": 900, "output_tokens": 20},
        },
        {
            "step": 2,
            "t": 3.1,
            "url": "http://127.0.0.1/r/x/",
            "text": None,
            "tool": "wait_for",
            "arguments": {"condition": "an email from Alice", "timeout": 300},
            "result": "condition met: Alice <alice@example.com> Budget",
            "screenshot": "transcript/step-002.jpg",
            "usage": {"input_tokens": 1200, "output_tokens": 31},
        },
    ]
    lines = [json.dumps(s) for s in steps]
    lines.append('{"step": 3, "t": 9.0, "text": "Alice wrote ab')  # the agent was killed here
    lines.append(
        json.dumps(
            {
                "step": 5,
                "t": 12.0,
                "tool": "visit_url",
                "arguments": {},
                "result": "",
                "screenshot": "transcript/step-005.jpg",
            }
        )
    )
    (task_folder / "transcript.jsonl").write_text("\n".join(lines) + "\n")


@pytest.mark.browser
def test_the_comparison_report_shows_both_agents_and_links_transcripts(two_agents, browser):
    page = browser.new_page()
    page.set_content("<body style='background:#2a7;font:40px sans-serif'>Inbox: Budget</body>")
    task = two_agents / "results" / "prompt" / "micromail" / "passive-abs"
    write_transcript(task, page.screenshot(type="jpeg"))
    report = two_agents / "out" / "compare.html"
    grade(two_agents, "prompt", "sleeper", "--html", str(report))
    html = report.read_text()
    assert "http://" not in html.replace('xmlns="http://www.w3.org/2000/svg"', "")

    page.goto(report.as_uri())
    success = page.locator("table#success tbody tr")
    assert success.all_inner_texts() == [
        "prompt\t5\t80.0% (4/5)\t75.0% (3/4)\t100.0% (1/1)\t100.0% (2/2)\t50.0% (1/2)"
        "\t100.0% (2/2)\t50.0% (1/2)",
        "sleeper\t5\t40.0% (2/5)\t0.0% (0/4)\t0.0% (0/1)\t100.0% (2/2)\t0.0% (0/2)"
        "\t50.0% (1/2)\t50.0% (1/2)",
    ]
    bars = page.locator("svg#plot-compare-success rect.mark")
    assert {bars.nth(i).get_attribute("data-set") for i in range(bars.count())} == {
        "prompt",
        "sleeper",
    }
    boxes = page.locator("svg#plot-compare-cost g.mark.box")
    assert [boxes.nth(i).get_attribute("data-set") for i in range(boxes.count())] == [
        "prompt",
        "sleeper",
    ]
    for box in boxes.all():  # both drawn inside the figure, on the log axis
        assert box.bounding_box()["width"] > 1
    # A task's rows for both agents sit next to each other; only prompt's has a transcript.
    rows = page.locator("table#tasks tbody tr").filter(has_text="passive-abs")
    first, second = (row.split("\t") for row in rows.all_inner_texts())
    assert first[:3] == ["passive-abs", "micromail", "prompt"] and first[-1] == "transcript"
    assert second[:3] == ["passive-abs", "micromail", "sleeper"] and second[-1] == "none"
    assert first[4:7] == ["yes", "yes", "5.0"] and second[4:7] == ["yes", "no", "117.5"]

    rows.first.locator("a.transcript").click()
    assert page.locator("h1").inner_text() == "passive-abs — prompt"
    assert page.locator("section.step:not(.unreadable) h2").all_inner_texts() == [
        "Step 1 t = 0.4 s",
        "Step 2 t = 3.1 s",
        "Step 5 t = 12.0 s",
    ]
    assert page.locator("code.tool").all_inner_texts() == ["visit_url", "wait_for", "visit_url"]
    screenshot = page.locator("img.screenshot")
    assert screenshot.count() == 1
    assert screenshot.evaluate("img => img.complete && img.naturalWidth") > 0
    assert "Line 3: unreadable, not JSON" in page.locator("section.unreadable").inner_text()
    assert page.locator("p.gap").inner_text() == "steps 3–4 missing from the transcript"
    assert "screenshot missing: transcript/step-005.jpg" in page.content()
    page.locator("a.back").click()
    assert page.url == report.as_uri()


def test_a_transcript_page_shows_what_it_cannot_read_and_never_crashes(two_agents):
    task = two_agents / "results" / "sleeper" / "micromail" / "noop"
    (task / "transcript.jsonl").write_bytes(
        b"[1, 2]\n"
        b'{"step": "two", "text": "<script>alert(1)</script>", "screenshot": "../../../x.jpg"}\n'
        b'{"step": 7, "tool": ["click"], "screenshot": 42, "usage": "lots", "result": {"a": 1}}\n'
        b"\xff\xfe not text\n"
    )
    report = two_agents / "report.html"
    grade(two_agents, "prompt", "sleeper", "--html", str(report))
    page = (
        report.parent / "report-transcripts" / "sleeper" / "micromail" / "noop.html"
    ).read_text()
    assert "Line 1: unreadable, not a JSON object" in page
    assert "Line 4: unreadable, not JSON" in page
    assert "Step ? (line 2)" in page and "Step 7" in page
    assert "<script>" not in page and "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    assert "screenshot outside the task folder: ../../../x.jpg" in page
    assert "screenshot: not a path: 42" in page and "usage: &quot;lots&quot;" in page
    assert '<code class="tool">[&quot;click&quot;]</code>' in page
    assert '<a class="transcript" href="report-transcripts/sleeper/micromail/noop.html">' in (
        report.read_text()
    )


def test_an_empty_transcript_says_so(two_agents):
    (two_agents / "results" / "prompt" / "micromail" / "noop" / "transcript.jsonl").write_text("")
    report = two_agents / "single.html"
    grade(two_agents, "prompt", "--html", str(report))
    page = report.parent / "single-transcripts" / "prompt" / "micromail" / "noop.html"
    assert "The transcript is empty." in page.read_text()
    assert 'href="single-transcripts/prompt/micromail/noop.html"' in report.read_text()


def test_without_any_price_the_cost_plot_falls_back_to_tokens(two_agents):
    (two_agents / "eval_config.yaml").write_text("agent_subprocess: [echo]\n")
    report = two_agents / "report.html"
    text = grade(two_agents, "prompt", "sleeper", "--html", str(report))
    assert table_rows(text, "Cost per task")["prompt"] == ["0", *["N/A"] * 6, "5"]
    assert table_rows(text, "Tokens per task")["prompt"][:3] == ["5", "212160", "204000"]
    html = report.read_text()
    assert "Tokens per task (input + output, log scale): no task has a priced model" in html
    assert "No price in the config for model(s): m, unpriced-model" in html

"""Grading and the HTML report from a results tree written by hand (no server needed)."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest
from django.core.management import call_command

RESULTS = {
    # name: (category, success, condition_at, contact_get_time, costs)
    "mail-passive": (
        "passive-absolute",
        True,
        60.0,
        75.0,
        {"input_tokens": 100_000, "output_tokens": 2_000, "tool_calls": 6, "model": "m"},
    ),
    "mail-active": (
        "active-relative",
        False,
        90.0,
        40.0,
        {"prompt_tokens": 300_000, "completion_tokens": 9_000, "tool_calls": 20, "model": "m"},
    ),
    "mail-noop": (
        "noop",
        True,
        None,
        None,
        {"input_tokens": 50_000, "output_tokens": 1_000, "tool_calls": 3, "model": "m"},
    ),
    "mail-late": ("passive-relative", True, 120.0, 130.0, None),
}


@pytest.fixture
def results_tree(tmp_path) -> Path:
    for name, (category, success, condition, contact, costs) in RESULTS.items():
        folder = tmp_path / "results" / "graded" / "micromail" / name
        folder.mkdir(parents=True)
        result = {
            "success": success,
            "detail": "",
            "evaluation_time": contact or 180.0,
            "condition_at": condition,
            "contact_get_time": contact,
            "contact_post_time": contact,
            "contact_message": None,
            "run": None,
            "category": category,
            "views": 30,
            "actions": 2,
        }
        (folder / "results.json").write_text(json.dumps(result))
        if costs:
            (folder / "costs.json").write_text(json.dumps(costs))
    (tmp_path / "eval_config.yaml").write_text(
        "agent_subprocess: [echo]\nprices: {m: {input: 1.25, output: 10}}\n"
    )
    return tmp_path


def grade(root: Path, *args) -> str:
    out = io.StringIO()
    call_command(
        "bench",
        "grade",
        "graded",
        "--results-dir",
        str(root / "results"),
        "--config",
        str(root / "eval_config.yaml"),
        *args,
        stdout=out,
    )
    return out.getvalue()


def test_grade_breaks_success_down_by_category_and_prices_the_tokens(results_tree):
    table = grade(results_tree)
    assert "Task Success Rate: 75.0% (3/4)" in table
    assert "noop 100.0% (1/1) | passive 100.0% (2/2) | active 0.0% (0/1)" in table
    assert "Reaction Time (successful, non-no-op): mean 12.5s, median 12.5s (n=2)" in table
    # 100k×1.25 + 2k×10 = 0.145; 300k×1.25 + 9k×10 = 0.465; 50k×1.25 + 1k×10 = 0.0725
    assert "Cost (USD): median $0.1450, mean $0.2275 (n=3)" in table
    assert "Tool Calls: mean 9.7, median 6.0, q1 4.5, q3 13.0, min 3, max 20" in table


def test_grade_filters_like_upstream(results_tree):
    assert "Total Tasks: 1" in grade(results_tree, "--task", "mail-noop")
    filtered = grade(results_tree, "--filter", "PASSIVE")
    assert "Total Tasks: 1" in filtered and "mail-passive" in filtered


@pytest.mark.parametrize("high", [0.0123, 1.0, 7.3, 99.9, 100.0, 362.41, 1234.5])
def test_axis_ticks_reach_the_largest_value(high):
    from apps.bench.report import nice_ticks

    ticks = nice_ticks(0, high)
    assert ticks[0] == 0 and ticks[-1] >= high and 2 <= len(ticks) <= 7


@pytest.mark.browser
def test_the_html_report_draws_four_plots_in_chromium(results_tree, browser):
    report = results_tree / "report.html"
    grade(results_tree, "--html", str(report))
    html = report.read_text()
    assert "http://" not in html.replace('xmlns="http://www.w3.org/2000/svg"', "")  # self-contained
    page = browser.new_page()
    page.goto(report.as_uri())
    for plot_id in ("plot-success", "plot-cost", "plot-time", "plot-cost-time"):
        svg = page.locator(f"svg#{plot_id}")
        assert svg.count() == 1
        box = svg.bounding_box()
        assert box["width"] > 100 and box["height"] > 100
        assert svg.locator(".mark").count() > 0, plot_id
    assert page.locator("svg#plot-time .diagonal").count() == 1
    # Successes are dots, failures crosses, on the completion-vs-target figure (no-ops excluded).
    assert page.locator("svg#plot-time circle.mark").count() == 2
    assert page.locator("svg#plot-time path.mark").count() == 1
    plot_box = page.locator("svg#plot-time").bounding_box()
    for mark in page.locator("svg#plot-time .mark").all():  # drawn inside the figure
        box = mark.bounding_box()
        assert (
            plot_box["y"] <= box["y"]
            and box["y"] + box["height"] <= plot_box["y"] + plot_box["height"]
        )
    assert page.locator("svg#plot-success rect.mark").count() == 6

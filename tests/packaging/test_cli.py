"""The `sentinel` command's own choices, in process: where its state and results go."""

from __future__ import annotations

from pathlib import Path

from sentinel_environments.cli import with_results_dir
from sentinel_site.locations import data_dir, user_data_dir

DATA = Path("/data")


def test_bench_run_and_grade_keep_results_in_the_data_folder_unless_told():
    assert with_results_dir(["run", "nightly"], DATA) == [
        "run", "nightly", "--results-dir", "/data/results",
    ]  # fmt: skip
    assert with_results_dir(["grade", "a", "--results-dir", "x"], DATA)[-1] == "x"
    assert with_results_dir(["grade", "a", "--results-dir=x"], DATA) == [
        "grade", "a", "--results-dir=x",
    ]  # fmt: skip
    assert with_results_dir(["validate", "--filter", "micromail"], DATA)[-1] == "micromail"


def test_state_goes_to_the_chosen_folder_else_the_users(tmp_path):
    assert data_dir({"SENTINEL_DATA_DIR": str(tmp_path)}) == tmp_path
    home = {"HOME": "/home/ada"}
    assert user_data_dir({**home, "XDG_DATA_HOME": "/xdg"}) == Path("/xdg/sentinel-environments")
    assert user_data_dir(home) == Path("/home/ada/.local/share/sentinel-environments")

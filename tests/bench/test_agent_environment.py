"""The agent's environment names no folder of the project (runner.agent_environment): what it
needs of the machine passes, every variable that would point it at the answer key does not."""

from __future__ import annotations

from pathlib import Path

from apps.bench.runner import agent_environment

PROJECT = (Path("/srv/sentinel"), Path("/srv/sentinel/.venv"), Path("/data/results"))


def test_the_project_is_named_by_no_variable_and_the_machine_still_is():
    harness = {
        "HOME": "/home/ada",
        "LANG": "C.UTF-8",
        "OPENAI_API_KEY": "sk-test",
        "PATH": "/srv/sentinel/.venv/bin:/usr/local/bin:/srv/sentinel/node_modules/.bin:/usr/bin",
        "PWD": "/srv/sentinel",
        "OLDPWD": "/tmp",
        "VIRTUAL_ENV": "/srv/sentinel/.venv",
        "PYTHONPATH": "/opt/lib",
        "DJANGO_SETTINGS_MODULE": "sentinel_site.settings",
        "SENTINEL_CONTROL_TOKEN": "secret",
        "PYTEST_CURRENT_TEST": "tests/bench/test_x.py::test_y (call)",
        "_": "/srv/sentinel/.venv/bin/python",
        "NOTES": "see /data/results/nightly",
    }
    env = agent_environment(harness, PROJECT)
    assert env == {
        "HOME": "/home/ada",
        "LANG": "C.UTF-8",
        "OPENAI_API_KEY": "sk-test",
        "PATH": "/usr/local/bin:/usr/bin",
    }


def test_a_folder_reached_through_a_link_is_named_either_way(tmp_path):
    real = tmp_path / "checkout"
    real.mkdir()
    link = tmp_path / "project"
    link.symlink_to(real)
    env = agent_environment({"A": f"{real}/x", "B": f"{link}/y", "C": "/usr"}, (link,))
    assert env == {"C": "/usr", "PATH": ""}


def test_a_path_entry_is_inside_a_folder_only_below_it():
    env = agent_environment({"PATH": "/srv/sentinel-tools/bin:/srv/sentinel/bin"}, PROJECT)
    assert env["PATH"] == "/srv/sentinel-tools/bin"

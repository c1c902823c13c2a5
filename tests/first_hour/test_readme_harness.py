"""The README's "Benchmarking an agent" followed literally on a fresh copy of the repository:
its `my_agent.py` and `eval_config.yaml` written as shown, its `bench run` and `bench grade`
commands run as shown (narrowed to one scenario with `--task`), and a graded result comes out.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import subprocess

import pytest

from tests.conftest import REPO

pytestmark = [pytest.mark.e2e, pytest.mark.user_clone]

TASK = "micromail-junk-relative-passive"


def readme_section(title: str) -> str:
    text = (REPO / "README.md").read_text(encoding="utf-8")
    start = text.index(f"## {title}\n")
    end = text.find("\n## ", start + 1)
    return text[start : end if end != -1 else None]


def code_blocks(section: str) -> list[tuple[str, str, str]]:
    """(language, code, the prose just before it) for every fenced block of the section."""
    blocks = []
    for match in re.finditer(r"```(\w*)\n(.*?)```", section, re.S):
        before = section[: match.start()].rstrip().splitlines()[-1]
        blocks.append((match.group(1), match.group(2), before))
    return blocks


def fresh_clone(target):
    """The repository's files as a clone would have them (tracked and new, never ignored)."""
    listed = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
        cwd=REPO,
        capture_output=True,
        check=True,
    ).stdout.decode()
    for name in filter(None, listed.split("\0")):
        source = REPO / name
        if source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)
    # `./dev` would create .venv on first use; the existing one has the same dependencies.
    (target / ".venv").symlink_to(REPO / ".venv")
    return target


def user_env() -> dict[str, str]:
    """A user's shell: none of the test suite's settings, databases or scenario folders."""
    return {
        key: value
        for key, value in os.environ.items()
        if not key.startswith(("DJANGO_", "SENTINEL_", "DATABASE_", "REDIS_", "CELERY_"))
    }


def command_line(code: str, prefix: str) -> list[str]:
    line = next(line for line in code.splitlines() if line.startswith(prefix))
    return shlex.split(line.split("#", 1)[0])


def test_the_readme_harness_example_works_as_written(tmp_path):
    clone = fresh_clone(tmp_path / "clone")
    blocks = code_blocks(readme_section("Benchmarking an agent"))
    agent = next(
        code for lang, code, before in blocks if lang == "python" and "my_agent.py" in before
    )
    config = next(code for lang, code, _ in blocks if lang == "yaml")
    commands = next(code for lang, code, _ in blocks if lang == "bash" and "bench run" in code)
    (clone / "my_agent.py").write_text(agent, encoding="utf-8")
    (clone / "eval_config.yaml").write_text(config, encoding="utf-8")
    env = user_env()

    run = [*command_line(commands, ".venv/bin/python manage.py bench run"), "--task", TASK]
    done = subprocess.run(run, cwd=clone, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr

    result = json.loads(
        (clone / "results" / "nightly" / "micromail" / TASK / "results.json").read_text()
    )
    assert isinstance(result["success"], bool) and result["contact_get_time"] is not None
    assert result["agent_exit_code"] == 0  # found my_agent.py, and httpx in the project's Python
    # The placeholder reports at once, before the condition: the console says why it failed,
    # with the agent's own last lines.
    assert f"FAILED {TASK}" in done.stdout and "before the condition held" in done.stdout
    assert "reported: 200" in done.stdout

    grade = command_line(commands, ".venv/bin/python manage.py bench grade")
    graded = subprocess.run(grade, cwd=clone, env=env, capture_output=True, text=True, timeout=300)
    assert graded.returncode == 0, graded.stdout + graded.stderr
    assert TASK in graded.stdout and (clone / "report.html").is_file()

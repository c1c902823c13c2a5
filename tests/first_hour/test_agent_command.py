"""The agent command of the README works from a fresh clone: its script is found beside the
config file, and `python` is the project's Python."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from apps.bench.config import load_config
from apps.bench.runner import AgentWorkspace, Harness, Task, output_tail


def test_a_script_beside_the_config_is_passed_by_its_path(tmp_path):
    (tmp_path / "my_agent.py").write_text("print('hi')\n")
    (tmp_path / "eval_config.yaml").write_text(
        'agent_subprocess: ["python", "my_agent.py", "--url", "__TASK_URL__", "missing.py"]\n'
    )
    config = load_config(tmp_path / "eval_config.yaml")
    argv, shell = config.agent_command({"__TASK_URL__": "http://x/r/t/start"})
    assert not shell
    assert argv == [
        "python",
        str(tmp_path / "my_agent.py"),
        "--url",
        "http://x/r/t/start",
        "missing.py",  # not a file beside the config: left as written
    ]


def test_python_is_the_projects_and_the_placeholders_name_it(tmp_path):
    (tmp_path / "eval_config.yaml").write_text(
        'agent_subprocess: ["__PYTHON__", "-c", "pass", "__TASK_DIR__"]\n'
    )
    harness = Harness(load_config(tmp_path / "eval_config.yaml"), None, tmp_path, tmp_path)
    task = Task("t", "micromail", {}, tmp_path / "micromail" / "t")
    run = {"task_url": "u", "contact_url": "c", "wait_url": "w"}
    with AgentWorkspace(task.folder) as workspace:
        argv, _, env = harness.command_for(task, run, "prompt", workspace)
        assert argv == [sys.executable, "-c", "pass", str(workspace.path)]
        assert env["SENTINEL_TASK_DIR"] == str(workspace.path)
        # `python` on the agent's PATH is the project's, run by a shim outside the project.
        python = shutil.which("python", path=env["PATH"])
        assert python is not None and not python.startswith(str(Path(sys.prefix)))
        ran = subprocess.run(
            ["python", "-c", "import sys; print(sys.prefix)"],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
        assert ran.stdout.strip() == sys.prefix


def test_the_last_lines_of_the_output_say_why(tmp_path):
    output = tmp_path / "output.txt"
    output.write_text("starting\n\n" + "".join(f"line {n}\n" for n in range(10)))
    assert output_tail(output) == ("line 5", "line 6", "line 7", "line 8", "line 9")
    assert output_tail(tmp_path / "absent.txt") == ()

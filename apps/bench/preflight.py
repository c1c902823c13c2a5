"""Checks made before the first task, so that a broken setup runs nothing instead of being
scored as the agent failing: the agent's command resolves (its program is found, a script it
names exists, a Python interpreter runs), every `__PLACEHOLDER__` in it is known, a configured
model endpoint answers one cheap request, and the server is reachable with scenarios to run.

Each check returns its problems, one line each; `bench run` prints them all and exits 2.
"""

from __future__ import annotations

import difflib
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import httpx

from apps.bench.config import BenchConfig, ReferenceAgent
from apps.bench.runner import PYTHON_NAMES, path_names, project_python, without_project

PLACEHOLDERS = (
    "__TASK_URL__",
    "__TASK_PROMPT__",
    "__BASE_DIR__",
    "__CONTACT_URL__",
    "__PYTHON__",
    "__TASK_DIR__",
)
PLACEHOLDER = re.compile(r"__[A-Z][A-Z0-9_]*__")
SCRIPT_SUFFIXES = (".py", ".sh", ".js", ".mjs", ".ts", ".rb", ".pl")
# Words a shell string may start with that are not programs on PATH.
SHELL_WORDS = frozenset(
    {"cd", "export", "exec", "env", "set", "source", ".", "if", "for", "while", "(", "{"}
)
PROBE_TIMEOUT_S = 10.0


def _known(arg: str) -> list[str]:
    """Problems with the placeholders of one argument (or of a whole shell string)."""
    problems = []
    for name in PLACEHOLDER.findall(arg):
        if name not in PLACEHOLDERS:
            close = difflib.get_close_matches(name, PLACEHOLDERS, n=1)
            hint = f"did you mean {close[0]}? " if close else ""
            problems.append(
                f"agent_subprocess: unknown placeholder {name} ({hint}known: {', '.join(PLACEHOLDERS)})"
            )
    return problems


def _static(arg: str, base_dir: Path) -> str:
    """An argument with the placeholders that are the same for every task filled in."""
    return arg.replace("__BASE_DIR__", str(base_dir)).replace("__PYTHON__", sys.executable)


def _agent_path(base_dir: Path) -> str:
    """The agent's PATH less the project's own folders (runner.agent_environment)."""
    return without_project(os.environ.get("PATH", ""), path_names((base_dir, *project_python())))


def _program(word: str, folder: Path | None, base_dir: Path) -> tuple[str | None, str | None]:
    """(the program's path, or None) and a problem when it cannot be found."""
    if "/" in word:
        path = Path(word) if Path(word).is_absolute() else (folder or Path.cwd()) / word
        if not path.is_file():
            return None, f"agent_subprocess: {word}: no such file"
        if not os.access(path, os.X_OK):
            return (
                None,
                f"agent_subprocess: {word}: not executable (chmod +x, or name its interpreter)",
            )
        return str(path), None
    if word in PYTHON_NAMES:  # the workspace's shims run the project's Python
        return sys.executable, None
    found = shutil.which(word, path=_agent_path(base_dir))
    if found is None:
        return None, f"agent_subprocess: {word}: no such program on PATH"
    return found, None


def _python_runs(program: str) -> str | None:
    """A Python interpreter must start (a broken virtualenv fails here, not in every task)."""
    if not Path(program).name.startswith("python"):
        return None
    try:
        done = subprocess.run(
            [program, "-c", "pass"], capture_output=True, timeout=PROBE_TIMEOUT_S, check=False
        )
    except (OSError, subprocess.TimeoutExpired) as error:
        return f"agent_subprocess: {program}: does not run ({error})"
    if done.returncode != 0:
        line = (done.stderr.decode(errors="replace").strip().splitlines() or ["?"])[-1]
        return f"agent_subprocess: {program}: does not run ({line})"
    return None


def _scripts(args: list[str], folder: Path | None, *, shell: bool) -> list[str]:
    """A script the command names (`my_agent.py`) must exist where the agent will look."""
    problems = []
    for arg in args:
        if PLACEHOLDER.search(arg) or arg.startswith("-") or not arg.endswith(SCRIPT_SUFFIXES):
            continue
        path = Path(arg)
        if path.is_absolute():
            if not path.is_file():
                problems.append(f"agent_subprocess: {arg}: no such file")
        elif shell:
            # A shell string runs in the task's folder and its files are not looked up beside
            # the config: only an absolute path (or __BASE_DIR__/…) finds them.
            problems.append(
                f"agent_subprocess: {arg}: a relative file in a shell string is looked for in "
                "the task's folder; give its absolute path, or use the list form"
            )
        elif folder is None or not (folder / arg).is_file():
            where = f"beside {folder}" if folder else "(no config file to look beside)"
            problems.append(f"agent_subprocess: {arg}: no such file {where}")
    return problems


def command_problems(config: BenchConfig, base_dir: Path) -> list[str]:
    """The agent_subprocess command: placeholders known, program found, scripts present."""
    command = config.agent_subprocess
    if command is None:
        return []
    shell = isinstance(command, str)
    raw = [command] if shell else list(command)
    problems = [p for arg in raw for p in _known(arg)]
    try:
        args = [_static(a, base_dir) for a in (shlex.split(command) if shell else command)]
    except ValueError as error:
        return [*problems, f"agent_subprocess: not a valid shell string: {error}"]
    if not args:
        return problems
    first = args[0]
    if not (shell and (first in SHELL_WORDS or "=" in first)) and not PLACEHOLDER.search(first):
        program, problem = _program(first, config.folder, base_dir)
        if problem:
            problems.append(problem)
        elif program:
            problems += filter(None, [_python_runs(program)])
    problems += _scripts(args[1:] if not shell else args, config.folder, shell=shell)
    return problems


def model_problems(agent: ReferenceAgent | None, *, timeout: float = PROBE_TIMEOUT_S) -> list[str]:
    """A reference agent's model endpoint answers `GET <base_url>/models` like an OpenAI API."""
    if agent is None:
        return []
    key = os.environ.get(agent.api_key_env, "")
    if agent.base_url is None:
        # The official API: no request from here (it costs a key and a network), but no key at
        # all would fail every task.
        if not key:
            return [f"agent: {agent.api_key_env} is not set (needed for the official API)"]
        return []
    url = f"{agent.base_url}/models"
    headers = {"Authorization": f"Bearer {key}"} if key else {}
    try:
        response = httpx.get(url, headers=headers, timeout=timeout)
    except httpx.HTTPError as error:
        return [f"agent.base_url: {url}: no answer ({type(error).__name__}: {error})"]
    kind = response.headers.get("content-type", "?").split(";")[0]
    if response.status_code >= 400:
        return [
            f"agent.base_url: {url}: HTTP {response.status_code} ({kind}): not a model endpoint"
        ]
    try:
        listed = response.json().get("data")
    except (ValueError, AttributeError):
        listed = None
    if not isinstance(listed, list):
        return [f"agent.base_url: {url}: answered {kind}, not an OpenAI-compatible model list"]
    return []


def reachable(server_url: str, *, timeout: float = PROBE_TIMEOUT_S) -> str | None:
    """A problem when a configured server does not answer at all (any HTTP answer will do:
    a wrong token or path is reported by the first real request, with its status)."""
    try:
        httpx.get(f"{server_url}/api/scenarios/", timeout=timeout)
    except httpx.HTTPError as error:
        return f"server_url: {server_url}: not reachable ({type(error).__name__}: {error})"
    return None


def server_problems(listing: list[dict], server: str) -> list[str]:
    """The server has at least one scenario to run."""
    if not listing:
        return [f"server {server}: no scenario to run (its scenario folder is empty or invalid)"]
    return []

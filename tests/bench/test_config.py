"""The eval_config.yaml rules: upstream's placeholders and command shapes, our keys, clear errors."""

from __future__ import annotations

import pytest

from apps.bench.config import ConfigError, load_config, parse_config
from apps.bench.runner import (
    CODE_DIR,
    LAUNCH_MODULE,
    Harness,
    Task,
    augment_prompt,
    category_of,
    deadline_s,
)

VALUES = {
    "__TASK_URL__": "http://h/r/t/start",
    "__CONTACT_URL__": "http://h/r/t/contact",
    "__TASK_PROMPT__": "it's a 'prompt'",
    "__BASE_DIR__": "/repo",
}


def test_a_list_command_substitutes_raw_substrings_without_a_shell():
    config = parse_config({"agent_subprocess": ["agent", "--url=__TASK_URL__", "__TASK_PROMPT__"]})
    assert config.agent_command(VALUES) == (
        ["agent", "--url=http://h/r/t/start", "it's a 'prompt'"],
        False,
    )


def test_a_string_command_quotes_each_value_and_uses_a_shell():
    config = parse_config(
        {"agent_subprocess": "bash __BASE_DIR__/run.sh __TASK_PROMPT__ __CONTACT_URL__"}
    )
    command, shell = config.agent_command(VALUES)
    assert shell is True
    assert command == "bash /repo/run.sh 'it'\"'\"'s a '\"'\"'prompt'\"'\"'' http://h/r/t/contact"


@pytest.mark.parametrize(
    "data, message",
    [
        (
            {"agent_subprocess": ["a"], "speed_factor": 0},
            "speed_factor: speed_factor must be positive",
        ),
        ({"agent_subprocess": ["a"], "parallel": 0}, "parallel: must be a positive integer"),
        ({"agent_subprocess": ["a"], "awake": -1}, "awake: must be 0 or a positive integer"),
        ({"agent_subprocess": ["a"], "awake": 1.5}, "awake: must be 0 or a positive integer"),
        (
            {"agent_subprocess": ["a"], "prices": {"m": {"input": -1}}},
            "prices.m.input: must be a number >= 0",
        ),
        (
            {"agent_subprocess": ["a"], "server_url": "localhost:8000"},
            "server_url: must be an http:// or https:// URL",
        ),
        ({"agent_subprocess": ["a"], "speedfactor": 2}, "speedfactor: unknown key"),
        (
            {"agent_subprocess": []},
            "agent_subprocess: a list must hold at least one string argument",
        ),
    ],
)
def test_bad_values_are_named_with_what_is_allowed(data, message):
    with pytest.raises(ConfigError, match=message.replace(".", r"\.")):
        parse_config(data, source="eval_config.yaml")


def test_awake_is_off_unless_asked_for():
    assert parse_config({"agent_subprocess": ["a"]}, source="c").awake == 0
    assert parse_config({"agent_subprocess": ["a"], "awake": 2}, source="c").awake == 2


def test_an_empty_file_is_an_empty_mapping_and_bad_yaml_names_the_line(tmp_path):
    path = tmp_path / "eval_config.yaml"
    path.write_text("")
    with pytest.raises(ConfigError, match="agent_subprocess: is required"):
        load_config(path)
    path.write_text("agent_subprocess: [a\nspeed_factor: 2\n")
    with pytest.raises(ConfigError, match="invalid YAML at line"):
        load_config(path)


def test_costs_accept_both_token_spellings():
    config = parse_config({"agent_subprocess": ["a"], "prices": {"m": {"input": 2, "output": 8}}})
    assert config.cost_usd(
        {"input_tokens": 1e6, "output_tokens": 1e5, "model": "m"}
    ) == pytest.approx(2.8)
    assert config.cost_usd(
        {"prompt_tokens": 1e6, "completion_tokens": 1e5, "model": "m"}
    ) == pytest.approx(2.8)
    assert config.cost_usd({"prompt_tokens": 1e6, "model": "unpriced"}) is None


def test_categories_deadlines_and_the_prompt():
    spec = {
        "condition_at": 10,
        "kill_at": 630,
        "taxonomy": {"monitoring_approach": "active", "milestone_type": "relative"},
    }
    assert category_of(spec) == "active-relative"
    assert category_of({**spec, "condition_at": None}) == "noop"
    assert deadline_s(spec, 4.0, 30.0) == 180.0  # kill_at_wall(4)
    assert deadline_s({**spec, "kill_at": 60}, 4.0, 30.0) == 45.0  # a short test scenario
    prompt = augment_prompt("Tell me.", "http://h/r/t/contact")
    assert (
        prompt.startswith("Tell me.\n\n")
        and "http://h/r/t/contact" in prompt
        and "ONLY ONCE" in prompt
    )


def test_resuming_skips_done_tasks_and_previous_errors_unless_retried(tmp_path):
    done, failed, fresh = (
        Task(n, "micromail", {}, tmp_path / n) for n in ("done", "failed", "fresh")
    )
    for task in (done, failed, fresh):
        task.folder.mkdir()
    (done.folder / "results.json").write_text("{}")
    (failed.folder / "error.txt").write_text("harness error: boom")
    harness = Harness(
        parse_config({"agent_subprocess": ["a"]}),
        client=None,
        results_root=tmp_path,
        base_dir=tmp_path,
    )
    assert [harness.should_skip(t) for t in (done, failed, fresh)] == [
        "already done",
        "previous error: harness error: boom; --retry-errors runs it again",
        None,
    ]
    harness.retry_errors = True
    assert harness.should_skip(failed) is None and not (failed.folder / "error.txt").exists()


def test_resuming_at_another_speed_says_so(tmp_path):
    task = Task("t", "micromail", {}, tmp_path / "t")
    task.folder.mkdir()
    (task.folder / "results.json").write_text('{"speed_factor": 1.0}')
    harness = Harness(
        parse_config({"agent_subprocess": ["a"], "speed_factor": 4}),
        client=None,
        results_root=tmp_path,
        base_dir=tmp_path,
    )
    assert harness.should_skip(task) == (
        "already done at speed 1, not 4: use a new NAME to compare speeds"
    )


class BrokenServer:
    """A control API that fails the way a crashed server does."""

    def create_run(self, scenario_id, speed_factor, clock_mode="live"):
        from apps.bench.client import HarnessError

        raise HarnessError("POST /api/runs/: HTTP 500: boom (after 3 attempts)")


def test_a_server_failure_is_a_harness_error_not_an_agent_failure(tmp_path):
    task = Task("t", "micromail", {"id": "t"}, tmp_path / "micromail" / "t")
    harness = Harness(
        parse_config({"agent_subprocess": ["a"]}),
        client=BrokenServer(),
        results_root=tmp_path,
        base_dir=tmp_path,
    )
    outcome = harness.run_task(task)
    assert outcome.status == "error"
    assert (
        (task.folder / "error.txt")
        .read_text()
        .startswith("harness error: POST /api/runs/: HTTP 500")
    )
    assert not (task.folder / "results.json").exists()


def test_the_progress_bar_redraws_one_line_on_a_tty():
    import io

    from apps.bench.runner import Outcome, Progress

    stream = io.StringIO()
    progress = Progress(stream, tty=True)
    task = Task("t", "micromail", {}, None)
    progress.begin(2)
    progress.started(task)
    progress.finished(Outcome(task, "passed"))
    progress.end()
    text = stream.getvalue()
    assert "\r\033[K[###############...............] done 1/2 running 0 passed 1" in text
    assert "Running" not in text  # plain lines are for logs, not terminals


REFERENCE = {"kind": "wait_for", "model": "gpt-4o", "base_url": "http://127.0.0.1:9/v1/"}


def test_a_reference_agent_is_configured_instead_of_a_command(tmp_path):
    config = parse_config({"agent": {**REFERENCE, "max_steps": 40}, "speed_factor": 4})
    agent = config.reference_agent
    assert (agent.kind, agent.model, agent.base_url, agent.api_key_env) == (
        "wait_for",
        "gpt-4o",
        "http://127.0.0.1:9/v1",
        "OPENAI_API_KEY",
    )
    task = Task("t", "micromail", {"condition_at": 60, "kill_at": 630}, tmp_path / "t")
    task.folder.mkdir()
    harness = Harness(config, client=None, results_root=tmp_path, base_dir=tmp_path)
    run = {"task_url": "http://h/r/t/start", "contact_url": "http://h/r/t/contact"}
    argv, shell, env = harness.command_for(task, run, "the prompt")
    # The code's folder reaches the module by its command line, never its environment.
    assert not shell and argv[1:5] == ["-c", LAUNCH_MODULE, str(CODE_DIR), "apps.browser_agent"]
    options = dict(zip(argv[5::2], argv[6::2], strict=False))
    assert options == {
        "--kind": "wait_for",
        "--model": "gpt-4o",
        "--api-key-env": "OPENAI_API_KEY",
        "--base-url": "http://127.0.0.1:9/v1",
        "--max-steps": "40",
        "--task-url": "http://h/r/t/start",
        "--contact-url": "http://h/r/t/contact",
        "--prompt-file": str((task.folder / "prompt.txt").resolve()),
        "--task-dir": str(task.folder.resolve()),  # and never the speed factor
        "--max-wall": repr(deadline_s(task.spec, 4.0, 30.0)),  # stops itself by the deadline
    }
    assert "PYTHONPATH" not in env


@pytest.mark.parametrize(
    "data, message",
    [
        ({"agent": {"kind": "nap", "model": "m"}}, "agent.kind: must be one of wait_for, sleep"),
        ({"agent": {"kind": "sleep"}}, "agent.model: must be a non-empty string"),
        ({"agent": {**REFERENCE, "temperature": 0}}, "agent.temperature: unknown key"),
        ({"agent": {**REFERENCE, "base_url": "localhost"}}, "base_url: must be an http"),
        ({"agent": {**REFERENCE, "max_steps": 0}}, "max_steps: must be a positive integer"),
        ({"agent": REFERENCE, "agent_subprocess": ["a"]}, "are exclusive"),
        ({"agent": "wait_for"}, "agent: must be a mapping"),
    ],
)
def test_a_bad_reference_agent_is_named(data, message):
    with pytest.raises(ConfigError, match=message):
        parse_config(data, source="eval_config.yaml")


def test_the_command_line_picks_the_reference_agent_and_overrides_its_model():
    from django.core.management.base import CommandError

    from apps.bench.management.commands.bench import reference_changes

    configured = parse_config({"agent": REFERENCE})
    changed = reference_changes(configured, "sleep", "qwen3.5:9b", "http://127.0.0.1:11434/v1")
    assert changed["agent_subprocess"] is None
    agent = changed["reference_agent"]
    assert (agent.kind, agent.model, agent.base_url) == (
        "sleep",
        "qwen3.5:9b",
        "http://127.0.0.1:11434/v1",
    )
    assert reference_changes(configured, None, None, None) == {}  # the config's own agent
    command_only = parse_config({"agent_subprocess": ["a"]})
    assert reference_changes(command_only, "oracle", None, None) == {}
    with pytest.raises(CommandError, match="--agent wait_for needs a model"):
        reference_changes(command_only, "wait_for", None, None)
    with pytest.raises(CommandError, match="not --agent oracle"):
        reference_changes(command_only, "oracle", "gpt-4o", None)

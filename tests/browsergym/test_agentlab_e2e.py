"""The scenarios as an AgentLab benchmark (sentinel_environments.agentlab): the task list with the
paper's categories as metadata, env args that register the tasks in a process that never
imported them (AgentLab's workers), and one experiment run by browsergym-experiments' own loop
— the one AgentLab runs for every task — on a real server and Debian's Chromium: an agent that
waits with noops to the end of a no-op scenario is graded a pass when the run ends."""

from __future__ import annotations

import pickle
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import pytest

from tests.conftest import REPO, ours

try:
    from browsergym.core import _get_global_playwright, _set_global_playwright
    from browsergym.experiments.agent import Agent, AgentInfo
    from browsergym.experiments.loop import AbstractAgentArgs, ExpArgs, get_exp_result

    from sentinel_environments.agentlab import benchmark
except ImportError as missing:  # the extra is part of ./dev's install
    pytest.fail(
        f"AgentLab's pieces are not installed ({missing}): pip install -e '.[agentlab]'",
        pytrace=False,
    )

NOOP = "sentinel.micromail-sender-absolute-noop"


def test_the_benchmark_holds_every_task_with_its_category():
    every = benchmark()
    assert len(every.env_args_list) == len(ours())
    assert set(every.task_metadata["category"]) == {"passive", "active", "noop"}
    noops = sum(s.is_noop for s in ours())
    assert len(every.subset_from_glob("category", "noop").env_args_list) == noops
    mail = len(ours("micromail"))
    assert len(every.subset_from_glob("environment", "micromail").env_args_list) == mail


def test_env_args_register_the_tasks_in_a_fresh_process():
    (noop,) = benchmark().subset_from_glob("task_name", NOOP).env_args_list
    probe = (
        "import pickle, sys, gymnasium as gym; env_args = pickle.load(sys.stdin.buffer); "
        "print(f'browsergym/{env_args.task_name}' in gym.registry)"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe],
        input=pickle.dumps(noop),
        capture_output=True,
        cwd=REPO,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr.decode()[-2000:]
    assert done.stdout.decode().strip() == "True"


class StaysToTheEnd(Agent):
    """Watches without ever reporting: two simulated minutes a step."""

    def obs_preprocessor(self, obs: dict) -> dict:
        # The loop counts the tokens of every text of the observation with tiktoken, whose
        # encoding is downloaded on first use: this agent reads none, so it keeps none.
        return {key: value for key, value in obs.items() if not isinstance(value, str)}

    def get_action(self, obs):
        return "noop(120000)", AgentInfo()


@dataclass
class StaysToTheEndArgs(AbstractAgentArgs):
    agent_name: str = "stays-to-the-end"

    def make_agent(self) -> Agent:
        return StaysToTheEnd()


@pytest.mark.e2e
@pytest.mark.browser
@pytest.mark.django_db(transaction=True)
def test_an_experiment_run_by_agentlabs_loop_passes_a_no_op_by_staying(live_site, tmp_path):
    (env_args,) = (
        benchmark(server_url=live_site, max_steps=20)
        .subset_from_glob("task_name", NOOP)
        .env_args_list
    )
    experiment = ExpArgs(agent_args=StaysToTheEndArgs(), env_args=env_args)
    experiment.prepare(tmp_path)

    def run() -> None:
        try:
            experiment.run()
        finally:  # BrowserGym's one Playwright, stopped in the thread that started it
            _get_global_playwright().stop()
            _set_global_playwright(None)

    with ThreadPoolExecutor(max_workers=1) as thread:
        thread.submit(run).result()
    summary = get_exp_result(experiment.exp_dir).summary_info
    assert summary["err_msg"] is None, summary["stack_trace"]
    assert summary["cum_reward"] == 1.0 and summary["terminated"] is True
    # 600 simulated seconds in skips of 120: done at the run's end, not by the step limit.
    assert summary["n_steps"] <= 6

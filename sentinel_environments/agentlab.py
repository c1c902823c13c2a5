"""The scenarios as an AgentLab benchmark (`pip install '.[agentlab]'`: the BrowserGym tasks of
`sentinel_environments.browsergym`, plus `browsergym-experiments` and pandas, which AgentLab's
`Benchmark` is made of):

    from agentlab.experiments.study import make_study
    from sentinel_environments.agentlab import benchmark

    study = make_study(agent_args, benchmark=benchmark(), n_jobs=4)
    study.run()

AgentLab runs each experiment in a worker process of its own, where nothing has registered
our tasks: every `SentinelEnvArgs` registers them again (same folder, server, clock and speed)
before it makes its environment, and unpickling one imports this module, which registers the
built-in tasks. The task metadata carries the paper's categories, so
`benchmark().subset_from_glob("category", "noop")` is the twenty no-op tasks.
"""

from __future__ import annotations

from dataclasses import dataclass

import pandas as pd
from browsergym.experiments.benchmark.base import Benchmark, HighLevelActionSetArgs
from browsergym.experiments.loop import EnvArgs

from sentinel_environments.browsergym import register_scenarios, task_metadata
from sentinel_environments.client import Clock

# BrowserGym's chat (send_msg_to_user), bid (click, fill, … and noop) and nav subsets.
ACTION_SUBSETS = ("chat", "bid", "nav")


@dataclass
class SentinelEnvArgs(EnvArgs):
    """AgentLab's `EnvArgs` for one of our tasks, registering the tasks where it makes the env."""

    scenario_folder: str | None = None
    server_url: str | None = None
    clock: Clock = "fast_forward"
    speed_factor: float = 1.0

    def make_env(self, action_mapping, exp_dir):
        register_scenarios(
            self.scenario_folder,
            server_url=self.server_url,
            clock=self.clock,
            speed_factor=self.speed_factor,
        )
        return super().make_env(action_mapping, exp_dir)


def benchmark(
    folder: str | None = None,
    *,
    server_url: str | None = None,
    clock: Clock = "fast_forward",
    speed_factor: float = 1.0,
    max_steps: int = 200,
    headless: bool = True,
    name: str = "sentinelbench",
) -> Benchmark:
    """Every scenario of `folder` (default: the built-in ones) as one AgentLab benchmark."""
    metadata = task_metadata(folder)
    return Benchmark(
        name=name,
        high_level_action_set_args=HighLevelActionSetArgs(subsets=ACTION_SUBSETS),
        is_multi_tab=False,
        supports_parallel_seeds=True,
        backends=[],  # nothing to prepare: each task starts its run (and, if need be, a server)
        env_args_list=[
            SentinelEnvArgs(
                task_name=row["task_name"],
                task_seed=0,
                max_steps=max_steps,
                headless=headless,
                scenario_folder=None if folder is None else str(folder),
                server_url=server_url,
                clock=clock,
                speed_factor=speed_factor,
            )
            for row in metadata
        ],
        task_metadata=pd.DataFrame(metadata),
    )

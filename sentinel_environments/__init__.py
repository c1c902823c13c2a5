"""Sentinel Environments from Python: a client of a running server's control API
(`sentinel_environments.client`), the `sentinel` command (`sentinel_environments.cli`) and,
with the `browsergym` extra, every scenario as a BrowserGym task
(`sentinel_environments.browsergym`).

Importing this package, or its client, needs neither Django nor the project's checkout: only
the standard library and httpx.
"""

from sentinel_environments.client import (
    Client,
    Run,
    ScenarioInfo,
    SentinelError,
    Verdict,
    WaitResult,
)

__all__ = ["Client", "Run", "ScenarioInfo", "SentinelError", "Verdict", "WaitResult"]

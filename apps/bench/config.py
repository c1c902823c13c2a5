"""The harness configuration file (upstream `eval_config.yaml`, plus our keys).

Upstream keys: `server_url`, `frontend_url`, `speed_factor`, `agent_subprocess` (a list: raw
substring substitution, no shell; a string: `shlex.quote`d substitution, run with a shell).
Ours: `parallel`, `prices`, `reaction_window`, `grace`, `control_token`, `http_timeout`,
`clock` (`live`, or `fast_forward`: the agent's declared waits skip the run's clock), `awake`
(fast-forward agents working at once on the embedded server, the others' waits held back: 0,
the default, for no pacing; sentinel_site/pacing.py), and
`agent` — one of the built-in reference agents (`apps.browser_agent`) instead of
`agent_subprocess`: `{kind: wait_for | sleep, model, base_url, api_key_env, max_steps,
max_tokens, max_wall}`.
Placeholders: __TASK_URL__, __TASK_PROMPT__, __BASE_DIR__, __CONTACT_URL__, and ours:
__PYTHON__ (the project's Python, with its packages), __TASK_DIR__ (the agent's folder)
and __WAIT_URL__ (the run's wait URL: skips its clock on a fast_forward run).
The agent runs in a fresh folder of its own (runner.AgentWorkspace: agents write `costs.json`
there, as upstream's did in the task's folder, and it is copied into the trial's `agent/`
folder); an argument of a list command naming a file beside the config file (`my_agent.py`) is given
as that file's absolute path, so the README's `["python", "my_agent.py", ...]` finds it.
"""

from __future__ import annotations

import dataclasses
import math
import shlex
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from events.timing import REACTION_WINDOW, SpeedFactorError, validate_speed_factor
from sentinel_site.yaml_files import YamlFileError, read_yaml

KNOWN_KEYS = (
    "server_url",
    "frontend_url",
    "speed_factor",
    "agent_subprocess",
    "parallel",
    "prices",
    "reaction_window",
    "grace",
    "control_token",
    "http_timeout",
    "api_url",
    "agent",
    "clock",
    "awake",
)
# Clocks a benchmark's runs can play on; the command line spells fast_forward fast-forward too.
BENCH_CLOCKS = ("live", "fast_forward")
REFERENCE_KINDS = ("wait_for", "sleep")
REFERENCE_KEYS = ("kind", "model", "base_url", "api_key_env", "max_steps", "max_tokens", "max_wall")
DEFAULT_GRACE = 90.0  # wall seconds an agent gets to exit once its run is completed (upstream)


class ConfigError(ValueError):
    """One line naming the file, the key and what is allowed."""


@dataclass(frozen=True)
class Price:
    input: float  # USD per 1M input tokens
    output: float  # USD per 1M output tokens


@dataclass(frozen=True)
class ReferenceAgent:
    """A built-in reference agent (`python -m apps.browser_agent`) on an OpenAI-compatible model."""

    kind: str  # "wait_for" | "sleep": the waiting tool it is given
    model: str
    base_url: str | None = None  # None: the official API, or $OPENAI_BASE_URL
    api_key_env: str = "OPENAI_API_KEY"  # the key's environment variable, never the key itself
    max_steps: int | None = None
    max_tokens: int | None = None  # input + output tokens per task
    max_wall: float | None = None  # wall seconds per task (the harness's deadline still holds)

    def arguments(self) -> list[str]:
        """Its command-line options, apart from the task's own."""
        argv = ["--kind", self.kind, "--model", self.model, "--api-key-env", self.api_key_env]
        if self.base_url:
            argv += ["--base-url", self.base_url]
        if self.max_steps is not None:
            argv += ["--max-steps", str(self.max_steps)]
        if self.max_tokens is not None:
            argv += ["--max-tokens-total", str(self.max_tokens)]
        if self.max_wall is not None:
            argv += ["--max-wall", repr(self.max_wall)]
        return argv


@dataclass(frozen=True)
class BenchConfig:
    agent_subprocess: list[str] | str | None
    reference_agent: ReferenceAgent | None = None
    server_url: str | None = None
    frontend_url: str | None = None
    speed_factor: float = 1.0
    parallel: int = 1
    prices: dict[str, Price] = field(default_factory=dict)
    reaction_window: float = REACTION_WINDOW
    grace: float = DEFAULT_GRACE
    control_token: str = ""
    http_timeout: float = 30.0
    clock: str = "live"  # one of BENCH_CLOCKS
    awake: int = 0  # the embedded server's SENTINEL_FAST_FORWARD_AWAKE (0: no pacing)
    noop_rule: str = "paper"  # one of outcomes.NOOP_RULES (--noop-rule)
    jitter: float = 0.0  # authored seconds a run's timeline may be shifted by (--jitter)
    seed: int = 0  # of the shifts (--seed)
    raw: dict[str, Any] = field(default_factory=dict)
    # The config file's folder, where relative agent files are found (None: no config file).
    folder: Path | None = None

    def agent_command(self, values: dict[str, str]) -> tuple[list[str] | str, bool]:
        """The agent command with placeholders filled in, and whether it needs a shell."""
        if isinstance(self.agent_subprocess, str):
            command = self.agent_subprocess
            for key, value in values.items():
                command = command.replace(key, shlex.quote(value))
            return command, True
        argv = []
        for arg in self.agent_subprocess or []:
            beside_config = self.folder is not None and _relative_file(self.folder, arg)
            if beside_config:
                argv.append(str(self.folder / arg))
                continue
            for key, value in values.items():
                arg = arg.replace(key, value)
            argv.append(arg)
        return argv, False

    def cost_usd(self, costs: dict[str, Any] | None) -> float | None:
        """USD cost of a costs.json sidecar, when its model has a price."""
        if not costs:
            return None
        price = self.prices.get(str(costs.get("model", "")))
        tokens_in, tokens_out = input_tokens(costs), output_tokens(costs)
        if price is None or (tokens_in is None and tokens_out is None):
            return None
        return ((tokens_in or 0) * price.input + (tokens_out or 0) * price.output) / 1e6


def _relative_file(folder: Path, arg: str) -> bool:
    """Whether `arg` is a relative path (no placeholder, no option) to a file in `folder`."""
    if not arg or arg.startswith("-") or "__" in arg or Path(arg).is_absolute():
        return False
    try:
        return (folder / arg).is_file()
    except OSError:  # e.g. an argument too long to be a path
        return False


def input_tokens(costs: dict[str, Any]) -> int | None:
    value = costs.get("input_tokens", costs.get("prompt_tokens"))
    return value if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def output_tokens(costs: dict[str, Any]) -> int | None:
    value = costs.get("output_tokens", costs.get("completion_tokens"))
    return value if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def _positive(
    data: dict, key: str, default: float, source: str, *, integer: bool = False, zero: bool = False
) -> Any:
    """`key`'s value: a positive number (an integer), or 0 too when `zero`."""
    value = data.get(key, default)
    if value is None:
        return default
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if integer:
        ok = ok and float(value).is_integer()
    if not ok or (value <= 0 and not zero) or value < 0:
        kind = "a positive integer" if integer else "a positive number"
        kind = f"0 or {kind}" if zero else kind
        raise ConfigError(f"{source}: {key}: must be {kind}, got {value!r}")
    return int(value) if integer else float(value)


def _url(data: dict, key: str, source: str) -> str | None:
    value = data.get(key)
    if value in (None, ""):
        return None
    if not isinstance(value, str) or not value.startswith(("http://", "https://")):
        raise ConfigError(f"{source}: {key}: must be an http:// or https:// URL, got {value!r}")
    return value.rstrip("/")


def bench_clock(value: Any, where: str) -> str:
    """`live` or `fast_forward` (also spelled fast-forward); ConfigError naming `where` else."""
    clock = value.replace("-", "_") if isinstance(value, str) else value
    if clock not in BENCH_CLOCKS:
        raise ConfigError(f"{where}: must be one of {', '.join(BENCH_CLOCKS)}, got {value!r}")
    return clock


def _prices(data: dict, source: str) -> dict[str, Price]:
    raw = data.get("prices") or {}
    if not isinstance(raw, dict):
        raise ConfigError(
            f"{source}: prices: must be a mapping model -> {{input, output}} (USD per 1M tokens)"
        )
    prices = {}
    for model, entry in raw.items():
        if not isinstance(entry, dict) or set(entry) - {"input", "output"}:
            raise ConfigError(
                f"{source}: prices.{model}: must be {{input: USD per 1M, output: USD per 1M}}, got {entry!r}"
            )
        values = {}
        for side in ("input", "output"):
            v = entry.get(side, 0)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or v < 0:
                raise ConfigError(
                    f"{source}: prices.{model}.{side}: must be a number >= 0, got {v!r}"
                )
            values[side] = float(v)
        prices[str(model)] = Price(**values)
    return prices


def _reference_agent(data: dict, source: str) -> ReferenceAgent | None:
    raw = data.get("agent")
    if raw is None:
        return None
    if not isinstance(raw, dict):
        raise ConfigError(
            f"{source}: agent: must be a mapping {{kind: wait_for | sleep, model: …, base_url: …}}"
        )
    unknown = sorted(set(raw) - set(REFERENCE_KEYS))
    if unknown:
        raise ConfigError(
            f"{source}: agent.{unknown[0]}: unknown key; allowed: {', '.join(REFERENCE_KEYS)}"
        )
    if raw.get("kind") not in REFERENCE_KINDS:
        raise ConfigError(
            f"{source}: agent.kind: must be one of {', '.join(REFERENCE_KINDS)}, "
            f"got {raw.get('kind')!r}"
        )
    for key in ("model", "api_key_env"):
        value = raw.get(key, "OPENAI_API_KEY" if key == "api_key_env" else None)
        if not isinstance(value, str) or not value.strip():
            raise ConfigError(f"{source}: agent.{key}: must be a non-empty string, got {value!r}")
    limits = {
        key: _positive(raw, key, None, f"{source}: agent", integer=key != "max_wall")
        for key in ("max_steps", "max_tokens", "max_wall")
        if raw.get(key) is not None
    }
    return ReferenceAgent(
        kind=raw["kind"],
        model=raw["model"],
        base_url=_url(raw, "base_url", f"{source}: agent"),
        api_key_env=raw.get("api_key_env", "OPENAI_API_KEY"),
        **limits,
    )


def parse_config(data: Any, *, source: str = "config", require_agent: bool = True) -> BenchConfig:
    if data is None:
        data = {}  # upstream: an empty file is {}
    if not isinstance(data, dict):
        raise ConfigError(f"{source}: must be a YAML mapping of keys ({', '.join(KNOWN_KEYS)})")
    unknown = sorted(set(data) - set(KNOWN_KEYS))
    if unknown:
        raise ConfigError(f"{source}: {unknown[0]}: unknown key; allowed: {', '.join(KNOWN_KEYS)}")
    agent = data.get("agent_subprocess")
    reference = _reference_agent(data, source)
    if agent is not None and reference is not None:
        raise ConfigError(
            f"{source}: agent: and agent_subprocess: are exclusive; keep the one to run"
        )
    if agent is None:
        if require_agent and reference is None:
            raise ConfigError(
                f"{source}: agent_subprocess: is required (a list of arguments or a shell string),"
                " or agent: {kind: wait_for | sleep, model: …} for a built-in reference agent"
            )
    elif isinstance(agent, list):
        if not agent or not all(isinstance(a, (str, int, float)) for a in agent):
            raise ConfigError(
                f"{source}: agent_subprocess: a list must hold at least one string argument"
            )
        agent = [str(a) for a in agent]
    elif not isinstance(agent, str) or not agent.strip():
        raise ConfigError(
            f"{source}: agent_subprocess: must be a list of arguments or a non-empty shell string"
        )
    try:
        speed_factor = validate_speed_factor(data.get("speed_factor", 1.0))
    except SpeedFactorError as exc:
        raise ConfigError(f"{source}: speed_factor: {exc}") from None
    token = data.get("control_token") or ""
    if not isinstance(token, str):
        raise ConfigError(f"{source}: control_token: must be a string")
    return BenchConfig(
        agent_subprocess=agent,
        reference_agent=reference,
        server_url=_url(data, "server_url", source) or _url(data, "api_url", source),
        frontend_url=_url(data, "frontend_url", source),
        speed_factor=speed_factor,
        parallel=_positive(data, "parallel", 1, source, integer=True),
        prices=_prices(data, source),
        reaction_window=_positive(data, "reaction_window", REACTION_WINDOW, source),
        grace=_positive(data, "grace", DEFAULT_GRACE, source, zero=True),
        control_token=token,
        http_timeout=_positive(data, "http_timeout", 30.0, source),
        clock=bench_clock(data.get("clock", "live"), f"{source}: clock"),
        awake=_positive(data, "awake", 0, source, integer=True, zero=True),
        raw=dict(data),
    )


def load_config(path: str | Path, *, require_agent: bool = True) -> BenchConfig:
    path = Path(path)
    try:
        data = read_yaml(path, "config file")
    except YamlFileError as exc:
        raise ConfigError(str(exc)) from None
    config = parse_config(data, source=str(path), require_agent=require_agent)
    return dataclasses.replace(config, folder=path.resolve().parent)

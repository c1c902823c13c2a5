"""Timing constants and rules of the SentinelBench protocol (upstream-protocol.md §3).

All scenario times are *authored* seconds. `speed_factor` only maps wall time to simulated
time (sim = wall × speed_factor); reports convert back to wall seconds (÷ speed_factor) so
figures compare with the paper.
"""

from __future__ import annotations

from typing import overload

MIN_CONDITION_AT = 10.0
MAX_CONDITION_AT = 600.0
REACTION_WINDOW = 30.0  # wall seconds
MAX_SPEED_FACTOR = 4.0
EVENT_BUFFER = REACTION_WINDOW * MAX_SPEED_FACTOR  # 120
EVENT_TIMELINE_END = MAX_CONDITION_AT + EVENT_BUFFER  # 720
KILL_AT = MAX_CONDITION_AT + REACTION_WINDOW  # 630


class SpeedFactorError(ValueError):
    pass


def validate_speed_factor(value: float) -> float:
    """Accept 0 < value ≤ MAX_SPEED_FACTOR; say which limit was broken otherwise."""
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise SpeedFactorError(f"speed_factor must be a number, got {value!r}") from None
    if not value > 0:  # also rejects NaN
        raise SpeedFactorError(
            f"speed_factor must be positive (0 < speed_factor <= {MAX_SPEED_FACTOR}), got {value}"
        )
    if value > MAX_SPEED_FACTOR:
        raise SpeedFactorError(
            f"speed_factor {value} is above MAX_SPEED_FACTOR ({MAX_SPEED_FACTOR}); allowed: 0 < speed_factor <= {MAX_SPEED_FACTOR}"
        )
    return value


def kill_at_wall(speed_factor: float) -> float:
    """Wall seconds after the run starts at which the harness stops the agent."""
    return MAX_CONDITION_AT / speed_factor + REACTION_WINDOW


@overload
def to_wall(sim_seconds: float, speed_factor: float) -> float: ...
@overload
def to_wall(sim_seconds: float | None, speed_factor: float) -> float | None: ...
def to_wall(sim_seconds: float | None, speed_factor: float) -> float | None:
    """Simulated seconds as wall seconds; None (a time that never came) stays None."""
    return None if sim_seconds is None else sim_seconds / speed_factor

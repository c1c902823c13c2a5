"""The reference agent's command line: its retry count is the user's to set, and a bad one is
one clear line."""

from __future__ import annotations

import pytest

from apps.browser_agent.__main__ import parser
from apps.browser_agent.model import DEFAULT_MAX_RETRIES

REQUIRED = ["--kind=sleep", "--model=m", "--task-url=u", "--contact-url=c", "--prompt=Go."]


def test_model_requests_are_retried_six_times_unless_told_otherwise():
    assert parser().parse_args(REQUIRED).max_retries == DEFAULT_MAX_RETRIES == 6
    assert parser().parse_args([*REQUIRED, "--max-retries=0"]).max_retries == 0


@pytest.mark.parametrize("value", ["-1", "1.5", "many"])
def test_a_bad_retry_count_is_refused_by_name(value, capsys):
    with pytest.raises(SystemExit) as exited:
        parser().parse_args([*REQUIRED, f"--max-retries={value}"])
    assert exited.value.code == 2
    said = capsys.readouterr().err
    assert "--max-retries" in said
    assert f"must be a non-negative whole number, got {value!r}" in said

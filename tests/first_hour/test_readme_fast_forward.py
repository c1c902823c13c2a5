"""The README's "Fast-forward" example run as written, by bash, curl and jq, against a real
server (only `localhost:8000` becomes the test server's address): its two waits answer as the
comments beside them say."""

from __future__ import annotations

import json
import shutil
import subprocess

import pytest

from tests.first_hour.test_readme_harness import code_blocks, readme_section

pytestmark = [pytest.mark.e2e, pytest.mark.django_db(transaction=True)]


def test_the_readme_fast_forward_example_answers_as_shown(live_site):
    if not (shutil.which("curl") and shutil.which("jq")):
        pytest.fail("the README example needs curl and jq: apt-get install -y curl jq")
    (script,) = [
        code for lang, code, _ in code_blocks(readme_section("Fast-forward")) if lang == "bash"
    ]
    host = live_site.removeprefix("http://")
    done = subprocess.run(
        ["bash", "-euo", "pipefail", "-c", script.replace("localhost:8000", host)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    change, sleep = answers(done.stdout)
    assert (change["sim_time"], change["why"]) == (3.26, "change")
    assert change["fired"] == [{"at": 3.26, "type": "new_email"}]
    assert sleep["why"] == "slept" and sleep["sim_time"] == pytest.approx(sleep["from"] + 6)
    assert sleep["fired"] == [{"at": 7.73, "type": "new_email"}]
    assert sleep["seq"] > change["seq"] and sleep["run_status"] == "running_auto"


def answers(output: str) -> list[dict]:
    """The JSON objects curl printed one after the other (without newlines between them)."""
    decoder, found, at = json.JSONDecoder(), [], 0
    while at < len(output.rstrip()):
        value, at = decoder.raw_decode(output, at)
        found.append(value)
        while at < len(output) and output[at].isspace():
            at += 1
    return found

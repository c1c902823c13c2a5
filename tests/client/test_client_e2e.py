"""The Python client (sentinel_environments.client) against a real server: a MicroMail passive
scenario driven end to end — created, opened, waited on in simulated time, acted on, reported,
graded and exported — and the server's refusals raised with its own one-line message."""

from __future__ import annotations

import subprocess
import sys

import pytest

from sentinel_environments import Client, SentinelError
from tests.conftest import REPO, ours

pytestmark = [pytest.mark.e2e, pytest.mark.django_db(transaction=True)]

KEVIN = "micromail-sender-absolute-passive"  # Kevin Lee's mail, base-77, arrives at 19.5 s


def test_a_passive_micromail_scenario_end_to_end(live_site):
    with Client(live_site) as sentinel:
        run = sentinel.create_run(KEVIN, clock="fast_forward", speed_factor=2)
        assert (run.scenario_id, run.environment, run.clock_mode) == (
            KEVIN,
            "micromail",
            "fast_forward",
        )
        assert run.prompt == "Tell me when I get an email from Kevin Lee."
        assert run.task_url.startswith(live_site) and run.contact_url.endswith("/contact")
        assert run.status == "ready"

        start_page = run.open()
        assert start_page.startswith(live_site) and "/micromail" in start_page
        arrived: list[float] = []
        while 19.5 not in arrived:
            waited = run.wait(until_change=True, timeout=60)
            assert waited.why == "change", waited
            arrived += [entry["at"] for entry in waited.fired]
        assert waited.sim_time == pytest.approx(19.5)
        assert run.refresh().status == "running_auto"

        opened = run.act("open_email", email_id="base-77")
        assert opened["action"] == "open_email" and opened["payload"] == {"email_id": "base-77"}
        run.contact("Kevin Lee has written to you.")

        verdict = run.evaluate()
        assert verdict.success, verdict.detail
        assert verdict.run == run.id and verdict.actions == 1
        assert verdict.contact_message == "Kevin Lee has written to you."
        # Wall seconds: a contact at the skip's moment is at most a few seconds late.
        assert verdict.condition_at == pytest.approx(19.5 / 2)
        assert 0 <= verdict.reaction_time < 30

        exported = run.export()
        assert exported[0]["run"]["scenario_id"] == KEVIN
        logged = run.events()
        assert [e["type"] for e in logged if e["kind"] == "action"] == ["open_email"]
        assert len(exported) == len(logged) + 1  # the header, then every event
        run.close()
        assert run.status == "completed"


def test_refusals_raise_the_servers_one_line_message(live_site):
    with Client(live_site) as sentinel:
        with pytest.raises(SentinelError) as unknown:
            sentinel.create_run("micromail-no-such-scenario")
        assert unknown.value.status == 404
        assert "micromail-no-such-scenario" in str(unknown.value)

        run = sentinel.create_run(KEVIN, clock="fast_forward")
        with pytest.raises(SentinelError) as early:
            run.wait(seconds=5)  # before the task is opened
        assert early.value.status == 409 and "\n" not in str(early.value)
        run.open()
        with pytest.raises(SentinelError) as bad:
            run.act("open_email", email_id="no-such-mail")
        assert bad.value.status == 400 or bad.value.status == 404
        assert "no-such-mail" in str(bad.value)

        live = sentinel.create_run(KEVIN)
        with pytest.raises(ValueError, match="needs a fast_forward run"):
            live.wait(until_change=True)

    with Client(live_site + "/nowhere-else:1") as elsewhere, pytest.raises(SentinelError):
        elsewhere.run(1)


def test_a_virtual_run_waits_by_advancing_its_clock(live_site):
    with Client(live_site) as sentinel:
        run = sentinel.create_run(KEVIN, clock="virtual")
        waited = run.wait(20)
        assert (waited.start, waited.sim_time) == (0, 20)
        assert [entry["at"] for entry in waited.fired] == [3.26, 7.73, 12.02, 16.07, 19.5]


def test_scenarios_are_listed_with_filters(live_site):
    with Client(live_site) as sentinel:
        every = list(sentinel.scenarios())
        passive = list(sentinel.scenarios(environment="micromail", category="passive"))
        easy = list(sentinel.scenarios(contains="micromail", difficulty="easy"))
        spec = sentinel.scenario(KEVIN)
    assert len(every) == len(ours())
    assert {s.category for s in every} == {"passive", "active", "noop"}
    assert KEVIN in {s.id for s in passive}
    assert all(s.environment == "micromail" and not s.noop for s in passive)
    assert easy and all(s.taxonomy["difficulty"] == "easy" for s in easy)
    assert spec["condition_at"] == 19.5


def test_the_client_imports_without_django():
    probe = "import sys, sentinel_environments.client; assert 'django' not in sys.modules"
    done = subprocess.run([sys.executable, "-c", probe], cwd=REPO, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_the_readme_example_runs_as_written(live_site, tmp_path):
    from tests.first_hour.test_readme_harness import code_blocks, readme_section

    (example,) = [c for lang, c, _ in code_blocks(readme_section("Use from Python")) if lang]
    script = tmp_path / "watch.py"
    script.write_text(example.replace("http://127.0.0.1:8000", live_site), encoding="utf-8")
    done = subprocess.run(
        [sys.executable, str(script)],
        cwd=tmp_path,
        env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"},
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    passive = [
        s
        for s in ours("micromail")
        if s.condition_at is not None and s.taxonomy.get("monitoring_approach") == "passive"
    ]
    assert lines[0] == f"{len(passive)} passive MicroMail scenarios"
    assert lines[1] == "Tell me when I get an email from Kevin Lee."
    assert lines[2].startswith("success: True reaction time: ")

"""loadscenarios + dumpscenarios reproduce every scenario file byte for byte."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError

from apps.scenarios.models import Scenario
from tests.conftest import OUR_SCENARIOS, REPO

pytestmark = pytest.mark.django_db


def files_of(root: Path) -> dict[str, bytes]:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*.json"))}


def round_trip(source: Path, target: Path) -> None:
    call_command("loadscenarios", str(source), stdout=io.StringIO(), stderr=io.StringIO())
    call_command("dumpscenarios", str(target), stdout=io.StringIO())


def test_our_scenarios_survive_load_and_dump_byte_identical(tmp_path):
    source = OUR_SCENARIOS
    round_trip(source, tmp_path)
    assert files_of(tmp_path) == files_of(source)


@pytest.mark.upstream
def test_upstream_scenarios_survive_load_and_dump_byte_identical(upstream_dir, tmp_path):
    source = upstream_dir / "scenarios"
    round_trip(source, tmp_path)
    original, dumped = files_of(source), files_of(tmp_path)
    assert sorted(dumped) == sorted(original)
    assert [name for name in original if dumped[name] != original[name]] == []


@pytest.mark.upstream
def test_two_upstream_files_sharing_an_id_are_two_rows(upstream_dir):
    call_command(
        "loadscenarios", str(upstream_dir / "scenarios"), stdout=io.StringIO(), stderr=io.StringIO()
    )
    shared = Scenario.objects.filter(
        path__in=[
            "microfy/playlists-relative-passive.json",
            "microfy/public-playlists-relative-passive.json",
        ]
    )
    assert shared.count() == 2
    assert len({row.scenario_id for row in shared}) == 1


def test_an_edited_row_is_dumped_with_the_edit_in_file_key_order(tmp_path):
    round_trip(OUR_SCENARIOS, tmp_path / "first")
    row = Scenario.objects.get(path="micromail/inbox-relative-passive.json")
    event = row.timeline.get(position=8)
    type(event).objects.filter(pk=event.pk).update(time=203.64)
    call_command("dumpscenarios", str(tmp_path / "second"), stdout=io.StringIO())
    text = (tmp_path / "second" / row.path).read_text()
    data = json.loads(text)
    original = json.loads((OUR_SCENARIOS / row.path).read_text())
    assert list(data) == list(original)
    assert data["events"][8]["time"] == 203.64
    assert data["event_timeline_end"] == 720.0 and "720.0" in text


def test_a_bad_file_is_one_line_naming_file_and_field(tmp_path):
    folder = tmp_path / "micromail"
    folder.mkdir()
    good = json.loads((REPO / "scenarios/micromail/inbox-relative-passive.json").read_text())
    (folder / "fine.json").write_text(json.dumps(good, indent=2) + "\n")
    good["condition_at"] = "soon"
    (folder / "broken.json").write_text(json.dumps(good, indent=2) + "\n")
    with pytest.raises(CommandError) as caught:
        call_command("loadscenarios", str(tmp_path), stdout=io.StringIO(), stderr=io.StringIO())
    message = str(caught.value)
    assert "broken.json" in message and "condition_at" in message and "\n" not in message
    assert not Scenario.objects.exists()


def test_invalid_json_names_the_line(tmp_path):
    (tmp_path / "micromail").mkdir()
    (tmp_path / "micromail" / "bad.json").write_text('{"id": "x",\n  oops}\n')
    with pytest.raises(CommandError, match=r"bad\.json: invalid JSON at line 2"):
        call_command("loadscenarios", str(tmp_path), stdout=io.StringIO(), stderr=io.StringIO())


def test_a_scenario_authored_in_the_admin_is_written_in_our_key_order():
    from apps.scenarios.format import parse_scenario
    from apps.scenarios.models import TimelineEvent
    from apps.scenarios.serialization import scenario_text

    row = Scenario.objects.create(
        path="micromail/new.json",
        scenario_id="micromail-new-absolute-passive",
        environment="micromail",
        prompt="Tell me when Kevin writes.",
        start_page="HOST_ADDRESS/micromail",
        condition_at=30.0,
        event_timeline_end=720.0,
        kill_at=630.0,
        eval_sql="SELECT 1",
        taxonomy={"milestone_type": "absolute", "monitoring_approach": "passive"},
    )
    TimelineEvent.objects.create(
        scenario=row, position=0, time=30.0, type="new_email", payload={"email_id": "base-04"}
    )
    data = json.loads(scenario_text(row))
    assert list(data) == [
        "id",
        "environment",
        "start_page",
        "prompt",
        "condition_at",
        "event_timeline_end",
        "kill_at",
        "events",
        "annotator_notes",
        "taxonomy",
        "eval_sql",
    ]
    assert parse_scenario(data).events[0] == {
        "time": 30.0,
        "type": "new_email",
        "payload": {"email_id": "base-04"},
    }


def write_scenario(folder: Path, name: str, **changes) -> dict:
    template = next(
        p for p in sorted((OUR_SCENARIOS / "micromail").glob("*.json")) if p.name != "dev.json"
    )
    data = json.loads(template.read_text())
    data.update(changes)
    (folder / "micromail").mkdir(parents=True, exist_ok=True)
    (folder / "micromail" / name).write_text(json.dumps(data, indent=2) + "\n")
    return data


def load(folder: Path, *args: str) -> str:
    out = io.StringIO()
    call_command("loadscenarios", str(folder), *args, stdout=out, stderr=io.StringIO())
    return out.getvalue()


def test_reloading_unchanged_files_replaces_nothing_and_says_so(tmp_path):
    write_scenario(tmp_path, "one.json")
    assert "(1 new, 0 replaced, 0 unchanged)" in load(tmp_path)
    assert "(0 new, 0 replaced, 1 unchanged)" in load(tmp_path)


def test_a_row_edited_in_the_admin_is_not_overwritten_without_replace(tmp_path):
    write_scenario(tmp_path, "one.json")
    load(tmp_path)
    Scenario.objects.filter(path="micromail/one.json").update(prompt="an author's unsaved work")
    write_scenario(tmp_path, "other.json", id="micromail-other")  # a new file alongside
    with pytest.raises(CommandError) as caught:
        load(tmp_path)
    message = str(caught.value)
    assert "micromail/one.json" in message and "--replace" in message and "dumpscenarios" in message
    assert Scenario.objects.get(path="micromail/one.json").prompt == "an author's unsaved work"
    assert not Scenario.objects.filter(path="micromail/other.json").exists()  # nothing imported
    assert "(1 new, 1 replaced, 0 unchanged)" in load(tmp_path, "--replace")
    assert Scenario.objects.get(path="micromail/one.json").prompt != "an author's unsaved work"


def test_a_file_of_the_same_path_from_another_folder_is_a_conflict_too(tmp_path):
    write_scenario(tmp_path / "ours", "one.json")
    write_scenario(tmp_path / "theirs", "one.json", prompt="someone else's dev scenario")
    load(tmp_path / "ours")
    with pytest.raises(CommandError, match="1 rows differ"):
        load(tmp_path / "theirs")

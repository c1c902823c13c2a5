"""The task timeline of a run no harness graded: drawn from its log alone, in the admin."""

from __future__ import annotations

import re

import pytest

from apps.replay.records import record_verdict

pytestmark = pytest.mark.django_db


def test_a_run_without_a_task_shows_its_log_on_the_axis_in_time_order(finished_run, admin_client):
    record_verdict(finished_run, source="test")
    page = admin_client.get(f"/admin/events/run/{finished_run.pk}/task/")
    assert page.status_code == 200
    html = page.content.decode()
    assert 'id="tl-axis"' in html and "No transcript" in html
    assert '<span class="tl-pass">pass</span>' in html
    moments = [float(at) for at in re.findall(r'data-at="([\d.]+)"', html)]
    assert moments == sorted(moments) and moments
    kinds = re.findall(r'<li id="tl-\d+" class="kind-(\w+)"', html)
    assert kinds.index("action") < kinds.index("contact")
    assert "the site at this moment" in html


def test_a_file_outside_the_task_folder_is_not_served(finished_run, admin_client):
    page = admin_client.get(f"/admin/events/run/{finished_run.pk}/task/file/../../etc/passwd")
    assert page.status_code == 404


def test_the_runs_admin_page_links_its_task_timeline(finished_run, admin_client):
    page = admin_client.get(f"/admin/events/run/{finished_run.pk}/change/").content.decode()
    assert f'href="/admin/events/run/{finished_run.pk}/task/">task timeline</a>' in page

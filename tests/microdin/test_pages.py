"""MicroDin's pages through the test client: what each screen shows, and what its forms do."""

from __future__ import annotations

from django.test import Client

from events import lifecycle
from events.commands import current_state
from tests.microdin.cast import KUBERNETES_JOB, LATE_JOB_AT

REQUIREMENT = "Hands-on Kubernetes operations"


def test_the_feed_shows_posts_with_counts_and_the_nav_badges(din_url):
    html = Client().get(din_url()).content.decode()
    assert "Silas Grant" in html and "Five years ago three of us" in html
    assert '35<span class="visually-hidden"> pending invitations' not in html
    assert '2<span class="visually-hidden"> pending invitations' in html
    assert '2<span class="visually-hidden"> unread messages' in html
    assert '1<span class="visually-hidden"> unread notifications' in html


def test_a_job_appears_when_posted_and_its_requirements_only_when_opened(din_run, din_url):
    browser = Client()
    assert browser.get(din_url(f"jobs/?job={KUBERNETES_JOB}")).status_code == 404
    lifecycle.advance(din_run, LATE_JOB_AT)
    listing = browser.get(din_url("jobs/")).content.decode()
    assert "Infrastructure Engineer" in listing and REQUIREMENT not in listing
    opened = browser.get(din_url(f"jobs/?job={KUBERNETES_JOB}")).content.decode()
    assert REQUIREMENT in opened and 'data-action="apply_job"' in opened


def test_applying_through_the_page_marks_the_job_applied(din_run, din_url):
    lifecycle.advance(din_run, LATE_JOB_AT)
    browser = Client()
    response = browser.post(din_url(f"jobs/{KUBERNETES_JOB}/apply"), follow=True)
    assert "Application sent to CloudPeak Hosting" in response.content.decode()
    assert current_state(din_run).job_states[KUBERNETES_JOB].is_applied
    again = browser.post(din_url(f"jobs/{KUBERNETES_JOB}/apply"))
    assert again.status_code == 409 and "already applied" in again.content.decode()


def test_opening_a_thread_marks_it_read(din_run, din_url):
    html = Client().get(din_url("messaging/?conversation=conv-02")).content.decode()
    assert "Found one edge case with muted boards" in html
    assert current_state(din_run).message_states["msg-02-2"].is_read


def test_clicking_a_notification_reads_it_and_goes_to_the_post(din_run, din_url):
    response = Client().post(din_url("notifications/read"), {"notification_id": "notif-01"})
    assert response.status_code == 302 and response.url.endswith("feed/update/post-self-1/")
    assert current_state(din_run).notification_states["notif-01"].is_read


def test_accepting_an_invitation_removes_it_from_the_list(din_run, din_url):
    browser = Client()
    browser.post(din_url("mynetwork/invitations/accept"), {"connection_id": "conn-01"})
    html = browser.get(din_url("mynetwork/invitations/")).content.decode()
    assert "Invitations (1)" in html and "Accept invitation from Kevin Lee" not in html
    assert "You are now connected with Kevin Lee" in html


def test_profiles_companies_and_search(din_url):
    browser = Client()
    me = browser.get(din_url("in/user000/")).content.decode()
    assert (
        "Chris Taylor" in me
        and "87 profile views" in me
        and 'data-action="add_profile_section"' in me
    )
    other = browser.get(din_url("in/user012/")).content.decode()
    assert 'data-action="start_conversation"' in other
    assert (
        "CloudPeak Hosting"
        in browser.get(din_url("company/org-cloudpeak-hosting/")).content.decode()
    )
    found = browser.get(din_url("search/?q=marco")).content.decode()
    assert "Marco Bellini" in found
    assert browser.get(din_url("in/nobody/")).status_code == 404
    assert browser.get(din_url("jobs/?filter=bogus")).status_code == 400

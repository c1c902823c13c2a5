"""Carrying out a solution step as a person would: through the environment's pages.

`Action.page(state, payload)` says where (a `PageStep`): open the page; unless its `form` is
None, submit the form marked `data-action="<action>"` there with those values, as a browser
does (tests/environments/forms.py), and follow the redirect. The CSRF token must come from the
page: the browser is a `Client(enforce_csrf_checks=True)`.
"""

from __future__ import annotations

import pytest
from django.test import Client

from apps.kit.links import contact_path, environment_root
from events.commands import current_state
from events.models import Event, EventKind, Run
from events.registry import Environment, PageStep, get_environment
from tests.environments.forms import NoSuchForm, find_submission


def browser() -> Client:
    return Client(enforce_csrf_checks=True)


def page_step(environment: Environment, state, step: dict) -> PageStep:
    """Where the step is done in the site; fails the test when the environment does not say."""
    name = step["action"]
    action = environment.actions.get(name)
    if action is None:
        pytest.fail(f"{environment.name} has no action {name!r} (solution step {step})")
    if action.page is None:
        pytest.fail(
            f"{environment.name} declares no page= for its action {name!r}, so the solution "
            f"step {step} cannot be carried out through the site: give Action(page=…) a "
            "function (state, payload) → PageStep"
        )
    return action.page(state, step["payload"])


def logged_actions(run: Run, name: str) -> int:
    return Event.objects.filter(run_id=run.pk, kind=EventKind.ACTION, type=name).count()


def perform_through_pages(client: Client, run: Run, step: dict) -> None:
    """Open the step's page, submit its form (if any), and check the action was logged."""
    environment = get_environment(run.environment)
    where = page_step(environment, current_state(run), step)
    name = step["action"]
    before = logged_actions(run, name)
    url = f"{environment_root(run)}/{where.path}"
    response = client.get(url)
    assert response.status_code == 200, f"GET {url} answered {response.status_code}"
    if where.form is not None:
        try:
            submission = find_submission(response.content.decode(), url, name, where.form)
        except NoSuchForm as exc:
            pytest.fail(f"{environment.name} {step}: {exc}")
        send = client.post if submission.method == "post" else client.get
        response = send(submission.url, submission.data, follow=True)
        assert response.status_code == 200, (
            f"{submission.method.upper()} {submission.url} answered {response.status_code}: "
            f"{response.content.decode()[:300]}"
        )
    assert logged_actions(run, name) > before, (
        f"{environment.name}: carrying out {step} through {url} logged no {name!r} action"
    )


def contact(client: Client, run: Run) -> None:
    """The agent says the condition is met: a visit of the run's contact page."""
    response = client.get(contact_path(run))
    assert response.status_code == 200, f"contact answered {response.status_code}"

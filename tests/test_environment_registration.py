"""Environment apps are found as Django's admin finds `admin.py`: an installed app with an
`environment` module is registered when Django starts, with the one `Environment` it declares."""

from __future__ import annotations

import sys
from dataclasses import replace
from importlib import import_module
from types import ModuleType

import pytest
from django.apps import apps
from django.core.exceptions import ImproperlyConfigured
from django.utils.module_loading import module_has_submodule

from apps.kit.environments import PARTS, declare, declared
from events.registry import environment_names, get_environment


def test_every_installed_app_with_an_environment_module_is_registered_with_its_declaration():
    found = {}
    for app in apps.get_app_configs():
        if module_has_submodule(app.module, "environment"):
            found[app.label] = declared(import_module(f"{app.name}.environment"))
    assert len(found) == 11  # the ten and the tests' tally
    assert sorted(environment.name for environment in found.values()) == environment_names()
    for environment in found.values():
        assert get_environment(environment.name) is environment


@pytest.mark.parametrize("count", [0, 2])
def test_a_module_that_declares_none_or_two_is_refused_by_name(count):
    module = ModuleType("apps.broken.environment")
    tally = get_environment("tally")
    for n in range(count):
        setattr(module, f"ENV{n}", replace(tally, name=f"tally{n}"))
    with pytest.raises(ImproperlyConfigured) as refused:
        declared(module)
    assert str(refused.value) == (
        "apps.broken.environment must declare exactly one events.registry.Environment; "
        f"it declares {count}"
    )


@pytest.fixture
def environment_module(monkeypatch):
    """An environment module `apps.microbroken.environment` part-way through its body, bound in
    `sys.modules` as Python binds a module while it runs."""
    module = ModuleType("apps.microbroken.environment")
    monkeypatch.setitem(sys.modules, module.__name__, module)
    return module


def test_a_declaration_takes_the_modules_parts_its_name_and_its_pages_by_convention(
    environment_module,
):
    mail = get_environment("micromail")
    for field, (name, _) in PARTS.items():
        setattr(environment_module, name, getattr(mail, field))
    declared_here = declare(environment_module.__name__, title="Broken", initial_state=dict)
    assert (declared_here.name, declared_here.title) == ("microbroken", "Broken")
    assert declared_here.urlconf == "apps.microbroken.urls"
    assert declared_here.actions is mail.actions and declared_here.event_types is mail.event_types
    assert declared_here.implicit_actions == ()  # IMPLICIT_ACTIONS is the one part left out
    environment_module.IMPLICIT_ACTIONS = mail.implicit_actions
    assert declare(environment_module.__name__, title="B", initial_state=dict).implicit_actions


def test_a_declaration_missing_parts_names_them(environment_module):
    environment_module.EVENT_TYPES = {}
    environment_module.ACTIONS = {}
    with pytest.raises(ImproperlyConfigured) as refused:
        declare(environment_module.__name__, title="Broken", initial_state=dict)
    assert str(refused.value) == (
        "apps.microbroken.environment declares its environment without BASELINES, materialize, "
        "sample_pages, SHOWN_COUNTS (bound in the module, or ACTIONS in its app's actions.py and "
        "sample_pages in its bench.py: apps.kit.environments.PARTS)"
    )


def test_a_declaration_takes_actions_and_sample_pages_from_their_modules():
    mail = get_environment("micromail")
    assert mail.actions is import_module("apps.micromail.actions").ACTIONS
    assert mail.sample_pages is import_module("apps.micromail.bench").sample_pages
    assert (
        get_environment("microhood").actions
        is vars(import_module("apps.microhood.environment"))["ACTIONS"]
    )  # bound by the environment module itself: settled first

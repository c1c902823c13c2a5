"""Environment apps are found as Django's admin finds `admin.py`: an installed app with an
`environment` module is registered when Django starts, with the one `Environment` it declares."""

from __future__ import annotations

from dataclasses import replace
from importlib import import_module
from types import ModuleType

import pytest
from django.apps import apps
from django.core.exceptions import ImproperlyConfigured
from django.utils.module_loading import module_has_submodule

from apps.kit.environments import declared
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

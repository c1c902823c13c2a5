"""Finding the environment apps, as Django's admin finds `admin.py`: an installed app with an
`environment` module is an environment, and the one `Environment` that module declares is
registered with the core when Django starts (`apps.kit.apps.KitConfig.ready`).

So an environment app needs no `apps.py`: adding `"apps.<env>"` to `INSTALLED_APPS` is all.
The core never imports environments; the kit hands each one to `events.registry.register`.
"""

from __future__ import annotations

from importlib import import_module
from types import ModuleType

from django.apps import apps
from django.core.exceptions import ImproperlyConfigured
from django.utils.module_loading import module_has_submodule

from events.registry import Environment, register

MODULE = "environment"  # the module an environment app declares its Environment in


def declared(module: ModuleType) -> Environment:
    """The one `Environment` bound in `module` (defined or imported alike: environments import none)."""
    found = [value for value in vars(module).values() if isinstance(value, Environment)]
    if len(found) != 1:
        raise ImproperlyConfigured(
            f"{module.__name__} must declare exactly one events.registry.Environment; "
            f"it declares {len(found)}"
        )
    return found[0]


def register_installed() -> None:
    """Register every installed environment app's `Environment`, in `INSTALLED_APPS` order."""
    for app in apps.get_app_configs():
        if module_has_submodule(app.module, MODULE):
            register(declared(import_module(f"{app.name}.{MODULE}")))

"""Finding the environment apps, as Django's admin finds `admin.py`: an installed app with an
`environment` module is an environment, and the one `Environment` that module declares is
registered with the core when Django starts (`apps.kit.apps.KitConfig.ready`).

So an environment app needs no `apps.py`: adding `"apps.<env>"` to `INSTALLED_APPS` is all.
The core never imports environments; the kit hands each one to `events.registry.register`.

The module names its parts by the house's names (`PARTS`) and `declare`s itself at its end, so
the wiring is said once here and not ten times:

    MICROMAIL = declare(__name__, title="MicroMail", initial_state=Mail.of)
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from importlib import import_module
from types import ModuleType
from typing import Any

from django.apps import apps
from django.core.exceptions import ImproperlyConfigured
from django.utils.module_loading import module_has_submodule

from events.registry import Environment, register

MODULE = "environment"  # the module an environment app declares its Environment in

# Environment field → the name the environment module binds it to (`ACTIONS` and `sample_pages`
# imported from actions.py and bench.py; the rest its own). `IMPLICIT_ACTIONS` may be left out.
PARTS = {
    "event_types": "EVENT_TYPES",
    "actions": "ACTIONS",
    "baselines": "BASELINES",
    "materialize": "materialize",
    "sample_pages": "sample_pages",
    "shown_counts": "SHOWN_COUNTS",
}


def declare(module: str, *, title: str, initial_state: Callable[[Any], Any]) -> Environment:
    """The `Environment` of the environment module `module` (its `__name__`, called at its end):
    its parts are the module's names in `PARTS`, its name the app's, its pages the app's
    `urls.py`. A part the module does not bind is named in the error."""
    names = vars(sys.modules[module])
    missing = [name for name in PARTS.values() if name not in names]
    if missing:
        raise ImproperlyConfigured(
            f"{module} must bind {', '.join(missing)} before it declares its environment "
            "(apps.kit.environments.PARTS)"
        )
    app = module.rpartition(".")[0]
    return Environment(
        name=app.rpartition(".")[2],
        title=title,
        initial_state=initial_state,
        urlconf=f"{app}.urls",
        implicit_actions=names.get("IMPLICIT_ACTIONS", ()),
        **{field: names[name] for field, name in PARTS.items()},
    )


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

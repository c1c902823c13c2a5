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


def declared(module: ModuleType) -> Environment:
    """The one `Environment` bound in `module` (defined or imported alike: environments import none)."""
    found = [value for value in vars(module).values() if isinstance(value, Environment)]
    if len(found) != 1:
        raise ImproperlyConfigured(
            f"{module.__name__} must declare exactly one events.registry.Environment; "
            f"it declares {len(found)}"
        )
    return found[0]


# Environment field → (the name its part is bound to, the app module it lives in). A part the
# environment module binds itself wins (MicroHood wraps its actions); `IMPLICIT_ACTIONS` may be
# left out.
_MISSING = object()
PARTS = {
    "event_types": ("EVENT_TYPES", MODULE),
    "actions": ("ACTIONS", "actions"),
    "baselines": ("BASELINES", MODULE),
    "materialize": ("materialize", MODULE),
    "sample_pages": ("sample_pages", "bench"),
    "shown_counts": ("SHOWN_COUNTS", MODULE),
}


def declare(module: str, *, title: str, initial_state: Callable[[Any], Any]) -> Environment:
    """The `Environment` of the environment module `module` (its `__name__`, called at its end):
    its parts are the names in `PARTS`, its name the app's, its pages the app's `urls.py`. The
    parts that are not where `PARTS` says are named in the error."""
    app = module.rpartition(".")[0]
    names = vars(sys.modules[module])

    def find(name: str, home: str) -> Any:
        if name in names or home == MODULE:
            return names.get(name, _MISSING)
        path = f"{app}.{home}"
        try:
            return getattr(import_module(path), name, _MISSING)
        except ModuleNotFoundError as absent:
            if not f"{path}.".startswith(f"{absent.name}."):
                raise  # not the module itself: something it imports is missing
            return _MISSING

    parts = {field: find(*where) for field, where in PARTS.items()}
    missing = [PARTS[field][0] for field, value in parts.items() if value is _MISSING]
    if missing:
        raise ImproperlyConfigured(
            f"{module} declares its environment without {', '.join(missing)} "
            "(bound in the module, or ACTIONS in its app's actions.py and sample_pages in its "
            "bench.py: apps.kit.environments.PARTS)"
        )
    return Environment(
        name=app.rpartition(".")[2],
        title=title,
        initial_state=initial_state,
        urlconf=f"{app}.urls",
        implicit_actions=names.get("IMPLICIT_ACTIONS", ()),
        **parts,
    )


def register_installed() -> None:
    """Register every installed environment app's `Environment`, in `INSTALLED_APPS` order."""
    for app in apps.get_app_configs():
        if module_has_submodule(app.module, MODULE):
            register(declared(import_module(f"{app.name}.{MODULE}")))

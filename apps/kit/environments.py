"""Registering an environment app with the core: one dotted path in its AppConfig.

    from apps.kit import environments

    class MicromailConfig(environments.EnvironmentConfig):
        name = "apps.micromail"
        environment = "apps.micromail.environment.MICROMAIL"

(Import the module, not the class: Django picks an app's config automatically only when its
apps.py defines exactly one AppConfig subclass.)

The core never imports environments; each one registers itself when Django starts.
"""

from __future__ import annotations

from django.apps import AppConfig
from django.core.exceptions import ImproperlyConfigured
from django.utils.module_loading import import_string

from events.registry import Environment, register


class EnvironmentConfig(AppConfig):
    environment: str = ""  # dotted path of the app's `Environment`

    def ready(self) -> None:
        if not self.environment:
            raise ImproperlyConfigured(f"{type(self).__name__} must name its `environment`")
        environment = import_string(self.environment)
        if not isinstance(environment, Environment):
            raise ImproperlyConfigured(f"{self.environment} is not an events.registry.Environment")
        register(environment)

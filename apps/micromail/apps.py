from django.apps import AppConfig


class MicromailConfig(AppConfig):
    name = "apps.micromail"
    label = "micromail"
    verbose_name = "MicroMail"

    def ready(self) -> None:
        # The core never imports environments: each one registers itself when Django starts.
        from apps.micromail.environment import MICROMAIL
        from events.registry import register

        register(MICROMAIL)

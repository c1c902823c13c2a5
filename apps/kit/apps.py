from django.apps import AppConfig


class KitConfig(AppConfig):
    name = "apps.kit"
    label = "kit"
    verbose_name = "Environment kit (pages, live regions, state helpers)"

    def ready(self) -> None:
        from apps.kit import environments, live, screen_cache
        from events.notifications import run_closed_signal

        environments.register_installed()  # every installed app with an `environment` module
        live.connect()  # live pages hear the engine's notices (events.notifications)
        # A closed run's kept pages are dropped, so memory comes back as runs end.
        run_closed_signal.connect(screen_cache.on_run_closed, dispatch_uid="kit.screens.closed")

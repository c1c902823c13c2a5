from django.apps import AppConfig


class KitConfig(AppConfig):
    name = "apps.kit"
    label = "kit"
    verbose_name = "Environment kit (pages, live regions, state helpers)"

    def ready(self) -> None:
        from apps.kit import live

        live.connect()  # live pages hear the engine's notices (events.notifications)

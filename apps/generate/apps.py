from django.apps import AppConfig


class GenerateConfig(AppConfig):
    name = "apps.generate"
    label = "generate"
    verbose_name = "Task generation (proven scenarios from the hand-written ones)"

from apps.kit import environments


class MicrohubConfig(environments.EnvironmentConfig):
    name = "apps.microhub"
    label = "microhub"
    verbose_name = "MicroHub"
    environment = "apps.microhub.environment.MICROHUB"

from apps.kit import environments


class MicrogramConfig(environments.EnvironmentConfig):
    name = "apps.microgram"
    label = "microgram"
    verbose_name = "MicroGram"
    environment = "apps.microgram.environment.MICROGRAM"

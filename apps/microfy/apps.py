from apps.kit import environments


class MicrofyConfig(environments.EnvironmentConfig):
    name = "apps.microfy"
    label = "microfy"
    verbose_name = "MicroFy"
    environment = "apps.microfy.environment.MICROFY"

from apps.kit import environments


class MicrochatConfig(environments.EnvironmentConfig):
    name = "apps.microchat"
    label = "microchat"
    verbose_name = "MicroChat"
    environment = "apps.microchat.environment.MICROCHAT"

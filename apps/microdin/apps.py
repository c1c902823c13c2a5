from apps.kit import environments


class MicrodinConfig(environments.EnvironmentConfig):
    name = "apps.microdin"
    label = "microdin"
    verbose_name = "MicroDin"
    environment = "apps.microdin.environment.MICRODIN"

from apps.agent_site import environments


class MicrodinConfig(environments.EnvironmentConfig):
    name = "apps.microdin"
    label = "microdin"
    verbose_name = "MicroDin"
    environment = "apps.microdin.environment.MICRODIN"

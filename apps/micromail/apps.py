from apps.kit import environments


class MicromailConfig(environments.EnvironmentConfig):
    name = "apps.micromail"
    label = "micromail"
    verbose_name = "MicroMail"
    environment = "apps.micromail.environment.MICROMAIL"

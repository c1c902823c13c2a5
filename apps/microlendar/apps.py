from apps.kit import environments


class MicrolendarConfig(environments.EnvironmentConfig):
    name = "apps.microlendar"
    label = "microlendar"
    verbose_name = "MicroLendar"
    environment = "apps.microlendar.environment.MICROLENDAR"

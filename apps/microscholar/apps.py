from apps.kit import environments


class MicroscholarConfig(environments.EnvironmentConfig):
    name = "apps.microscholar"
    label = "microscholar"
    verbose_name = "MicroScholar"
    environment = "apps.microscholar.environment.MICROSCHOLAR"

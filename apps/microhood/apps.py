from apps.kit import environments


class MicrohoodConfig(environments.EnvironmentConfig):
    name = "apps.microhood"
    label = "microhood"
    verbose_name = "MicroHood"
    environment = "apps.microhood.environment.MICROHOOD"

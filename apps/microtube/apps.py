from apps.kit import environments


class MicrotubeConfig(environments.EnvironmentConfig):
    name = "apps.microtube"
    label = "microtube"
    verbose_name = "MicroTube"
    environment = "apps.microtube.environment.MICROTUBE"

from apps.agent_site import environments


class MicroscholarConfig(environments.EnvironmentConfig):
    name = "apps.microscholar"
    label = "microscholar"
    verbose_name = "MicroScholar"
    environment = "apps.microscholar.environment.MICROSCHOLAR"

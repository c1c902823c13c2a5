from apps.kit import environments


class TallyConfig(environments.EnvironmentConfig):
    name = "apps.tally"
    label = "tally"
    verbose_name = "Tally (test environment)"
    environment = "apps.tally.environment.TALLY"

from django.apps import AppConfig


class AgentSiteConfig(AppConfig):
    name = "apps.agent_site"
    label = "agent_site"
    verbose_name = "Agent-facing site shell"

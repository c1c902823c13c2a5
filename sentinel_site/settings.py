"""Settings for Sentinel Environments, driven by environment variables.

Embedded defaults need nothing installed: SQLite (WAL), the in-memory channel layer and the
in-process ticker. Set DATABASE_URL / REDIS_URL / SENTINEL_TICKER=celery for production.
"""

from sentinel_site.config import (
    database_from_url,
    env_bool,
    env_choice,
    env_dir,
    env_int,
    env_networks,
    env_rate,
    env_str,
    env_url,
)
from sentinel_site.locations import RESOURCES_DIR, data_dir

# A checkout's top folder, or the installed package's copy of its folders (locations.py).
BASE_DIR = RESOURCES_DIR
# State (the SQLite database, logs): var/ of a checkout, else SENTINEL_DATA_DIR or a per-user folder.
VAR_DIR = data_dir()

SECRET_KEY = env_str("SENTINEL_SECRET_KEY", "dev-insecure-change-me-for-any-public-deployment")
DEBUG = env_bool("SENTINEL_DEBUG", False)
# The loopback names only, unless widened: a foreign Host header (DNS rebinding: a web page whose
# name resolves to 127.0.0.1) is refused before it can read anything.
ALLOWED_HOSTS = [
    h for h in env_str("SENTINEL_ALLOWED_HOSTS", "localhost,127.0.0.1,[::1]").split(",") if h
]
# The largest request body accepted, refused before it is read (sentinel_site/request_limits.py)
# and again by every JSON door (apps/control/parsers.py). 2.5 MB is Django's own default.
DATA_UPLOAD_MAX_MEMORY_SIZE = env_int("SENTINEL_MAX_BODY_BYTES", 2_621_440, minimum=1024)
# What one client can hold of the server, at the socket (sentinel_site/request_limits.py).
SENTINEL_MAX_CONNECTIONS_PER_CLIENT = env_int(
    "SENTINEL_MAX_CONNECTIONS_PER_CLIENT", 1024, minimum=1
)
SENTINEL_HEADER_DEADLINE_S = env_int("SENTINEL_HEADER_DEADLINE_S", 10, minimum=1)
SENTINEL_IDLE_TIMEOUT_S = env_int("SENTINEL_IDLE_TIMEOUT_S", 75, minimum=1)
CSRF_TRUSTED_ORIGINS = [o for o in env_str("SENTINEL_CSRF_TRUSTED_ORIGINS").split(",") if o]

INSTALLED_APPS = [
    "daphne",
    "django.contrib.admin",
    "django.contrib.auth",
    "django.contrib.contenttypes",
    "django.contrib.sessions",
    "django.contrib.messages",
    "django.contrib.staticfiles",
    "django.contrib.humanize",  # intcomma: counts as products print them (1,847)
    "rest_framework",
    "drf_spectacular",
    "drf_spectacular_sidecar",  # Swagger UI's files, served locally (/api/docs/)
    "channels",
    "django_htmx",
    "events",
    "apps.scenarios",
    "apps.generate",  # task generation: after apps.scenarios, whose admin it extends
    "apps.control",
    "apps.kit",
    "apps.bench",
    "apps.replay",
    "apps.media",  # generated images shared by the environments (not an environment itself)
    "apps.home",  # the home page at / (generic over the registered environments)
    # Environments: one line each. The core never imports them; each app registers its
    # Environment with the core registry when Django starts (AppConfig.ready).
    "apps.micromail",
    "apps.microhub",
    "apps.microtube",
    "apps.microhood",
    "apps.microgram",
    "apps.microfy",
    "apps.microscholar",
    "apps.microlendar",
    "apps.microdin",
    "apps.microchat",
]

# Django's stock middleware, run as one synchronous chain (see sentinel_site/http_handler.py).
MIDDLEWARE = [
    "django.middleware.security.SecurityMiddleware",
    "django.contrib.sessions.middleware.SessionMiddleware",
    "django.middleware.common.CommonMiddleware",
    "django.middleware.csrf.CsrfViewMiddleware",
    "django.contrib.auth.middleware.AuthenticationMiddleware",
    "django.contrib.messages.middleware.MessageMiddleware",
    "django.middleware.clickjacking.XFrameOptionsMiddleware",
    "django_htmx.middleware.HtmxMiddleware",
    "apps.kit.sim_clock_header.SimClockHeaderMiddleware",  # the run's clock, for agents
]

ROOT_URLCONF = "sentinel_site.urls"
ASGI_APPLICATION = "sentinel_site.asgi.application"
WSGI_APPLICATION = None

TEMPLATES = [
    {
        "BACKEND": "django.template.backends.django.DjangoTemplates",
        "DIRS": [BASE_DIR / "templates"],
        "APP_DIRS": True,
        "OPTIONS": {
            "context_processors": [
                "django.template.context_processors.request",
                "django.contrib.auth.context_processors.auth",
                "django.contrib.messages.context_processors.messages",
            ],
        },
    },
]

DATABASES = {
    "default": database_from_url(
        "DATABASE_URL",
        env_url(
            "DATABASE_URL",
            f"sqlite:///{VAR_DIR / 'sentinel.sqlite3'}",  # var/sentinel.sqlite3 in a checkout
            schemes=("sqlite", "postgres", "postgresql"),
        ),
        base=BASE_DIR,
    )
}
DEFAULT_AUTO_FIELD = "django.db.models.BigAutoField"

REDIS_URL = env_url("REDIS_URL", "", schemes=("redis", "rediss"))
if REDIS_URL:
    CHANNEL_LAYERS = {
        "default": {
            "BACKEND": "channels_redis.core.RedisChannelLayer",
            "CONFIG": {"hosts": [REDIS_URL]},
        }
    }
else:
    CHANNEL_LAYERS = {"default": {"BACKEND": "channels.layers.InMemoryChannelLayer"}}

SENTINEL_TICKER = env_choice("SENTINEL_TICKER", ("inprocess", "celery", "off"), "inprocess")
CELERY_BROKER_URL = env_url(
    "CELERY_BROKER_URL", REDIS_URL or "memory://", schemes=("redis", "rediss", "amqp", "memory")
)
CELERY_TASK_IGNORE_RESULT = True
# Beat's schedule file is runtime state, not source: under var/ with the SQLite database.
CELERY_BEAT_SCHEDULE_FILENAME = str(VAR_DIR / "celerybeat-schedule")

# Runs one client address may create ("<n>/<sec|min|hour|day>" or "off"; apps/control/throttling.py).
SENTINEL_RUN_CREATION_RATE = env_rate("SENTINEL_RUN_CREATION_RATE", "1000/min")
# The proxies in front of the server (addresses or networks) whose X-Forwarded-For is believed:
# none by default, so a client is its connection's address and no header can change it.
SENTINEL_TRUSTED_PROXIES = env_networks("SENTINEL_TRUSTED_PROXIES")
# Fast-forward agents working at once (per web process); the others' waits are held back while
# their clocks run (sentinel_site/pacing.py). 0, the default: no pacing — agents that wait on a
# remote model would only queue for places they do not load; `bench run --awake` sets it.
SENTINEL_FAST_FORWARD_AWAKE = env_int("SENTINEL_FAST_FORWARD_AWAKE", 0)
# Entries an agent may add to its run's log (actions and page views; events/commands.py).
SENTINEL_AGENT_LOG_BUDGET = env_int("SENTINEL_AGENT_LOG_BUDGET", 20_000, minimum=1)
# Bytes of payload (JSON) the agent may store in its run's log, over all its entries.
SENTINEL_AGENT_BYTES_BUDGET = env_int("SENTINEL_AGENT_BYTES_BUDGET", 16 * 1024 * 1024, minimum=1)
# Runs older than this many days are deleted by the ticker once a day (events/retention.py).
SENTINEL_RUN_RETENTION_DAYS = env_int("SENTINEL_RUN_RETENTION_DAYS", 30)
SENTINEL_CONTROL_TOKEN = env_str("SENTINEL_CONTROL_TOKEN")
# The upstream flat endpoints (/init, /redirect, /contact, …) drive one shared default slot that
# any caller can reach; off, only a run's own URLs touch a run (apps/control/slot.py).
SENTINEL_FLAT_ENDPOINTS = env_bool("SENTINEL_FLAT_ENDPOINTS", True)
# Keep each rendered agent page while nothing it shows can change (apps/kit/screen_cache.py);
# off only to measure or debug rendering itself.
SENTINEL_SCREEN_CACHE = env_bool("SENTINEL_SCREEN_CACHE", True)
SENTINEL_CATALOG_DIR = env_dir("SENTINEL_CATALOG_DIR", BASE_DIR / "fixtures", base=BASE_DIR)
SENTINEL_SCENARIO_DIR = env_dir("SENTINEL_SCENARIO_DIR", BASE_DIR / "scenarios", base=BASE_DIR)

LANGUAGE_CODE = "en-us"
TIME_ZONE = "UTC"
USE_I18N = False
USE_TZ = True

STATIC_URL = "static/"
STATIC_ROOT = BASE_DIR / "staticfiles"
STATICFILES_DIRS = [BASE_DIR / "static"] if (BASE_DIR / "static").is_dir() else []

REST_FRAMEWORK = {
    "DEFAULT_SCHEMA_CLASS": "drf_spectacular.openapi.AutoSchema",
    "DEFAULT_AUTHENTICATION_CLASSES": [],
    "DEFAULT_PERMISSION_CLASSES": [
        "apps.control.auth.SameOriginPermission",
        "apps.control.auth.ControlTokenPermission",
    ],
    "EXCEPTION_HANDLER": "apps.control.errors.exception_handler",
    "DEFAULT_PARSER_CLASSES": [
        # JSON only, through the door (size, UTF-8, depth, text, numbers): no form or multipart
        # body, which any web page could post here without its visitor knowing.
        "apps.control.parsers.StrictJSONParser",
    ],
    "UNAUTHENTICATED_USER": None,
    # DRF's own client identity (BaseThrottle.get_ident) believes X-Forwarded-For unless told how
    # many proxies there are: none. Ours is apps.control.throttling.client_address.
    "NUM_PROXIES": 0,
}
SPECTACULAR_SETTINGS = {
    "TITLE": "Sentinel Environments control API",
    "DESCRIPTION": "Create, drive, evaluate and close benchmark runs.",
    "VERSION": "1",
    "SERVE_PERMISSIONS": ["apps.control.auth.ControlTokenPermission"],
    "PREPROCESSING_HOOKS": ["apps.control.schema.only_api_paths"],
    "SWAGGER_UI_DIST": "SIDECAR",  # no CDN: the files come from drf-spectacular-sidecar
    "SWAGGER_UI_FAVICON_HREF": "SIDECAR",
    "REDOC_DIST": "SIDECAR",
}

LOGGING = {
    "version": 1,
    "disable_existing_loggers": False,
    "handlers": {"console": {"class": "logging.StreamHandler"}},
    "root": {"handlers": ["console"], "level": env_str("SENTINEL_LOG_LEVEL", "WARNING").upper()},
}

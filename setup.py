"""The package's file list, which pyproject.toml cannot say alone: the code's packages, plus the
checkout's top-level templates/, static/, fixtures/ and scenarios/ shipped inside the package as
`sentinel_environments/resources/<folder>` (found there by sentinel_site/locations.py)."""

from setuptools import find_packages, setup

RESOURCES = ("templates", "static", "fixtures", "scenarios")
CODE = ["apps", "apps.*", "events", "events.*", "sentinel_site", "sentinel_site.*"]

setup(
    packages=[
        *find_packages(include=[*CODE, "sentinel_environments", "sentinel_environments.*"]),
        *(f"sentinel_environments.resources.{folder}" for folder in RESOURCES),
    ],
    package_dir={f"sentinel_environments.resources.{folder}": folder for folder in RESOURCES},
)

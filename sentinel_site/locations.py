"""Where the site's files are, in a checkout and in an installed package.

In a checkout (`manage.py` beside the packages) everything is where git has it: templates,
static files, catalogs and scenarios at the top, state in `var/`. Installed from a wheel
(`pip install .`, then `sentinel serve`), the code sits in site-packages and those four folders
are shipped inside the package, as `sentinel_environments/resources/<folder>` (setup.py); the
state then goes to a per-user folder, never beside the code: `SENTINEL_DATA_DIR` (which
`sentinel --data DIR` sets), else `$XDG_DATA_HOME/sentinel-environments`, else
`~/.local/share/sentinel-environments`.
"""

from __future__ import annotations

import os
from pathlib import Path

CODE_DIR = Path(__file__).resolve().parent.parent
IS_CHECKOUT = (CODE_DIR / "manage.py").is_file()
# The folder holding templates/, static/, fixtures/ and scenarios/ (BASE_DIR of the settings).
RESOURCES_DIR = CODE_DIR if IS_CHECKOUT else CODE_DIR / "sentinel_environments" / "resources"


def user_data_dir(environ: os._Environ[str] | dict[str, str] = os.environ) -> Path:
    """The per-user folder of an installed package's state (database, logs, results)."""
    xdg = environ.get("XDG_DATA_HOME", "").strip()
    home = Path(environ.get("HOME") or Path.home())
    root = Path(xdg) if xdg else home / ".local" / "share"
    return root / "sentinel-environments"


def data_dir(environ: os._Environ[str] | dict[str, str] = os.environ) -> Path:
    """Where state goes: SENTINEL_DATA_DIR, else `var/` of a checkout, else the user's folder."""
    chosen = environ.get("SENTINEL_DATA_DIR", "").strip()
    if chosen:
        return Path(chosen).expanduser().resolve()
    return CODE_DIR / "var" if IS_CHECKOUT else user_data_dir(environ)

"""The `sentinel` command, installed with the package (`pip install .`), working from any folder:

    sentinel serve [--host H] [--port P] [--data DIR]   the site, admin and control API (Daphne)
    sentinel bench run|grade|validate …                  the harness (`manage.py bench`)
    sentinel admin migrate|createsuperuser|…             any of the site's management commands

State — the SQLite database, logs, `bench` results — goes to `--data DIR` (before or, for
`serve`, after the command), else `SENTINEL_DATA_DIR`, else `var/` of a checkout, else the
per-user folder (`$XDG_DATA_HOME/sentinel-environments`, by default
`~/.local/share/sentinel-environments`); see sentinel_site/locations.py. Every other setting is
the environment variable the README's "Configuration" lists.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

USAGE_EPILOG = (
    "State goes to --data DIR, SENTINEL_DATA_DIR or ~/.local/share/sentinel-environments."
)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="sentinel",
        description="Sentinel Environments: synthetic web apps on scripted timelines, for "
        "benchmarking monitoring agents.",
        epilog=USAGE_EPILOG,
    )
    data_help = "the folder of the database, logs and results (created if missing)"
    parser.add_argument("--data", metavar="DIR", help=data_help)
    commands = parser.add_subparsers(dest="command", required=True)
    serve = commands.add_parser("serve", help="serve the site, the admin and the control API")
    serve.add_argument("--host", default=os.environ.get("HOST", "127.0.0.1"))
    serve.add_argument("--port", type=int, default=int(os.environ.get("PORT", "8000")))
    # SUPPRESS: a subcommand's default would overwrite `sentinel --data DIR serve`.
    serve.add_argument("--data", metavar="DIR", default=argparse.SUPPRESS, help=data_help)
    commands.add_parser(
        "bench",
        add_help=False,
        help="the benchmark harness: run | grade | validate (`sentinel bench --help`)",
    )
    commands.add_parser(
        "admin",
        add_help=False,
        help="a management command: migrate, createsuperuser, … (`sentinel admin help`)",
    )
    return parser


def _setup(data: str | None) -> Path:
    """Point the settings at the data folder and start Django; answers the data folder."""
    if data:
        os.environ["SENTINEL_DATA_DIR"] = str(Path(data).expanduser().resolve())
    os.environ.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")
    from sentinel_site.locations import data_dir

    folder = data_dir()
    folder.mkdir(parents=True, exist_ok=True)
    import django

    django.setup()
    return folder


def _migrate() -> None:
    from django.core.management import call_command

    call_command("migrate", interactive=False, verbosity=0)


def serve(host: str, port: int, data: str | None) -> int:
    from sentinel_site.exposure import announcement, control_token_for

    # Beyond loopback, never without a control token: one is made up and printed if unset.
    token = control_token_for(host, dict(os.environ))
    if token:
        print(announcement(host, token), file=sys.stderr)
        os.environ["SENTINEL_CONTROL_TOKEN"] = token
    folder = _setup(data)
    _migrate()
    print(
        f"Sentinel Environments on http://{host}:{port}/  (admin: /admin/, API: /api/runs/, "
        f"schema: /api/schema/; data: {folder})\n"
        "Create an admin login with: sentinel admin createsuperuser",
        flush=True,
    )
    # -P: the folder the command runs from is not on the path, so nothing there named like
    # one of our packages (an `apps/` of the user's) can stand in for it.
    daphne = [sys.executable, "-P", "-m", "daphne", "-b", host, "-p", str(port)]
    os.execv(sys.executable, [*daphne, "sentinel_site.asgi:application"])
    return 0  # not reached


def with_results_dir(args: list[str], data: Path) -> list[str]:
    """`bench run` and `bench grade` keep their result sets in the data folder unless told
    otherwise (`manage.py bench` keeps `results/` of the folder it runs from)."""
    if args[:1] not in (["run"], ["grade"]) or any(
        a == "--results-dir" or a.startswith("--results-dir=") for a in args
    ):
        return args
    return [*args, "--results-dir", str(data / "results")]


def bench(args: list[str], data: str | None) -> int:
    folder = _setup(data)
    _migrate()
    from django.core.management import execute_from_command_line

    execute_from_command_line(["sentinel", "bench", *with_results_dir(args, folder)])
    return 0


def admin(args: list[str], data: str | None) -> int:
    _setup(data)
    from django.core.management import execute_from_command_line

    execute_from_command_line(["sentinel admin", *(args or ["help"])])
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    parser = _parser()
    options, rest = parser.parse_known_args(argv)
    if options.command == "serve":
        if rest:
            parser.error(f"serve: unknown arguments: {' '.join(rest)}")
        return serve(options.host, options.port, options.data)
    if options.command == "bench":
        return bench(rest, options.data)
    return admin(rest, options.data)


if __name__ == "__main__":
    sys.exit(main())

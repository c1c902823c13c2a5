"""The installable package (issue #32): the checkout built into a wheel, installed in a fresh
virtual environment, and its one command run from a folder that is not the checkout —
`sentinel serve` serves the home page, `sentinel bench validate --filter micromail-sender` (a
passive scenario and a no-op) passes, and
the state lands in `--data DIR` or the documented per-user folder. Nothing of the checkout is on
the path: the code, templates, catalogs and scenarios all come from the installed package.

The wheel is built with build isolation (pip fetches setuptools from the package index, or its
cache); the temporary environment takes the dependencies from the project's own (a `.pth` line
naming its site-packages), so nothing else is downloaded. Slow by nature — a build, a server
start and a validation of two scenarios by seven agents, about a minute — and
marked `e2e`; every step is bounded by its own timeout.
"""

from __future__ import annotations

import subprocess
import sys
import sysconfig
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from sentinel_site.site_server import free_port, stop_process_group
from tests.conftest import REPO, ours
from tests.first_hour.test_readme_harness import fresh_clone

pytestmark = pytest.mark.e2e


def run(command: list, *, timeout: float, **kwargs) -> subprocess.CompletedProcess:
    done = subprocess.run(command, capture_output=True, text=True, timeout=timeout, **kwargs)
    assert done.returncode == 0, f"{command}: exit {done.returncode}\n{done.stdout}\n{done.stderr}"
    return done


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    """A virtual environment with the wheel built from a fresh copy of the checkout installed."""
    root = tmp_path_factory.mktemp("package")
    clone = fresh_clone(root / "clone")
    run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", str(clone), "-w", str(root)],
        timeout=300,
        cwd=root,
    )
    (wheel,) = root.glob("sentinel_environments-*.whl")
    venv = root / "venv"
    run([sys.executable, "-m", "venv", "--without-pip", str(venv)], timeout=60)
    (site,) = venv.glob("lib/python*/site-packages")
    (site / "project-dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    # The project's environment knows a "sentinel-environments" of its own (./dev installs the
    # checkout there): installed here regardless, where this environment looks first.
    pip = [venv / "bin" / "python", "-m", "pip", "install", "-q", "--no-deps", "--ignore-installed"]
    run([*pip, str(wheel)], timeout=120, cwd=root)
    return venv


def user_env(home: Path) -> dict[str, str]:
    """A user's shell: no variable of the test suite (settings, databases, scenario folders)."""
    return {"PATH": "/usr/bin:/bin", "HOME": str(home), "LANG": "C.UTF-8"}


def test_sentinel_serve_from_another_folder_serves_the_home_page(installed, tmp_path):
    elsewhere, data = tmp_path / "elsewhere", tmp_path / "data"
    elsewhere.mkdir()
    env = user_env(tmp_path / "home")
    sentinel = str(installed / "bin" / "sentinel")

    where = run(
        [sentinel, "--data", str(data), "admin", "shell", "--no-imports", "-c",
         "import sentinel_site; from django.conf import settings; "
         "print(sentinel_site.__file__, settings.BASE_DIR, settings.SENTINEL_SCENARIO_DIR, "
         "settings.DATABASES['default']['NAME'], sep='\\n')"],
        timeout=120, cwd=elsewhere, env=env,
    ).stdout.split()[-4:]  # fmt: skip
    assert all(not path.startswith(str(REPO)) for path in where), where
    assert all(path.startswith(str(installed)) for path in where[:3]), where
    assert where[3] == str(data / "sentinel.sqlite3")

    port = free_port()
    log = tmp_path / "serve.log"
    with open(log, "wb") as out:
        server = subprocess.Popen(
            [sentinel, "serve", "--port", str(port), "--data", str(data)],
            cwd=elsewhere, env=env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True,
        )  # fmt: skip
    try:
        page = home_page(f"http://127.0.0.1:{port}/", server, log)
    finally:
        stop_process_group(server)
    assert "<title>Sentinel Environments" in page
    assert "micromail" in page.lower()
    assert f"data: {data}" in log.read_text()


def home_page(url: str, server: subprocess.Popen, log: Path, startup_s: float = 120) -> str:
    deadline = time.monotonic() + startup_s
    while True:
        try:
            with urllib.request.urlopen(url, timeout=10) as answer:
                return answer.read().decode()
        except (urllib.error.URLError, ConnectionError):
            if server.poll() is not None or time.monotonic() > deadline:
                pytest.fail(f"sentinel serve did not answer:\n{log.read_text()}")
            time.sleep(0.2)


def test_sentinel_bench_validate_passes_and_state_goes_to_the_user_folder(installed, tmp_path):
    elsewhere, home = tmp_path / "elsewhere", tmp_path / "home"
    elsewhere.mkdir()
    done = run(
        [str(installed / "bin" / "sentinel"), "bench", "validate", "--filter", "micromail-sender"],
        timeout=600, cwd=elsewhere, env=user_env(home),
    )  # fmt: skip
    summary = done.stdout.strip().splitlines()[-1]
    mail = [s for s in ours("micromail") if s.id.startswith("micromail-sender")]
    n, targeted = len(mail), sum(not s.is_noop for s in mail)
    assert summary.startswith(
        f"bench_validate: scenarios={n} oracle={n}/{n} early_fail={targeted}/{targeted}"
    ), summary
    # No --data, no SENTINEL_DATA_DIR: the documented per-user folder.
    assert (home / ".local" / "share" / "sentinel-environments" / "sentinel.sqlite3").is_file()
    assert list(elsewhere.iterdir()) == []  # nothing written where the command ran


def test_sentinel_without_a_command_says_what_it_takes(installed, tmp_path):
    done = subprocess.run(
        [str(installed / "bin" / "sentinel")], capture_output=True, text=True, timeout=60,
        cwd=tmp_path, env=user_env(tmp_path),
    )  # fmt: skip
    assert done.returncode == 2
    assert "serve" in done.stderr and "bench" in done.stderr and "admin" in done.stderr


def test_the_installed_package_says_its_version_and_licence(installed):
    """What `pip show` and a package index read: the version, the MIT licence (the original
    SentinelBench's) as an SPDX expression, and the licence text itself shipped beside it."""
    (dist_info,) = installed.glob("lib/python*/site-packages/sentinel_environments-*.dist-info")
    metadata = (dist_info / "METADATA").read_text()
    assert "\nVersion: 0.1.0\n" in metadata
    assert "\nLicense-Expression: MIT\n" in metadata
    assert "Permission is hereby granted" in (dist_info / "licenses" / "LICENSE").read_text()

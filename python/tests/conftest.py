"""Fixtures of the Python package's tests (run by tests/python.rs under scripts/test, against
the wheel installed into a fresh venv): the brdfbake binary built by cargo, whose files and
messages the package must reproduce, and a working directory of each test's own."""

import json
import os
import shutil
import subprocess
from pathlib import Path
from typing import List

import pytest


@pytest.fixture(autouse=True)
def _own_directory(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every test runs in an empty directory: no presets/ folder, built-in presets only (the
    CLI would read ./presets first, as the package does)."""
    monkeypatch.chdir(tmp_path)


class Cli:
    """The brdfbake binary built by cargo (BRDFBAKE_BIN), run in the current directory."""

    def __init__(self, path: str) -> None:
        self.path = path

    def run(self, *args: str) -> subprocess.CompletedProcess:
        env = {k: v for k, v in os.environ.items() if k != "RAYON_NUM_THREADS"}
        return subprocess.run(
            [self.path, *args], capture_output=True, text=True, env=env, timeout=600
        )

    def ok(self, *args: str) -> str:
        r = self.run(*args)
        assert r.returncode == 0, f"brdfbake {' '.join(args)}: {r.stderr}"
        return r.stdout

    def json(self, *args: str) -> dict:
        return json.loads(self.ok(*args, "--json"))

    def error(self, *args: str, code: int = 2) -> str:
        """The message of a command that fails with exit `code` (after `error: `)."""
        r = self.run(*args)
        assert r.returncode == code, f"brdfbake {' '.join(args)}: exit {r.returncode}: {r.stderr}"
        assert r.stderr.startswith("error: "), r.stderr
        return r.stderr[len("error: "):]


@pytest.fixture(scope="session")
def cli() -> Cli:
    path = os.environ.get("BRDFBAKE_BIN") or shutil.which("brdfbake")
    assert path, "set BRDFBAKE_BIN to the brdfbake binary (tests/python.rs does)"
    return Cli(path)


def files(folder: Path) -> List[str]:
    """The names of the files in `folder`, sorted."""
    return sorted(p.name for p in folder.iterdir())

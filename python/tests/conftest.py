"""Shared fixtures: the `kappa` command line (the Rust library's own output) and paths."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PYTHON_DIR = ROOT / "python"


def find_cli():
    """The `kappa` binary: $KAPPA_CLI, else a build in the repository's target/."""
    env = os.environ.get("KAPPA_CLI")
    if env:
        return Path(env)
    for profile in ("debug", "release"):
        for target in (os.environ.get("CARGO_TARGET_DIR"), ROOT / "target"):
            if target and (Path(target) / profile / "kappa").is_file():
                return Path(target) / profile / "kappa"
    found = shutil.which("kappa")
    return Path(found) if found else None


@pytest.fixture(scope="session")
def kappa_cli():
    """Runs `kappa ARGS` and returns its stdout; skips when the binary is not built (CI sets
    KAPPA_CLI, so there it fails instead)."""
    cli = find_cli()
    if cli is None or not cli.is_file():
        if os.environ.get("KAPPA_CLI"):
            pytest.fail(f"KAPPA_CLI={os.environ['KAPPA_CLI']} does not exist")
        pytest.skip("the kappa command line is not built (cargo build --features cli)")

    def run(*args, stdin=None):
        r = subprocess.run(
            [str(cli), *args], input=stdin, capture_output=True, text=True, check=False
        )
        return r

    return run

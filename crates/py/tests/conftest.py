"""Shared fixtures: the repository root, the `slipload` command line to compare against,
and scratch folders."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


def cli_path() -> pathlib.Path:
    """The command line built from this checkout (scripts/test.sh builds it and names it
    in SLIPLOAD_BIN; else the release build)."""
    given = os.environ.get("SLIPLOAD_BIN")
    path = pathlib.Path(given) if given else ROOT / "target" / "release" / "slipload"
    if not path.is_file():
        raise RuntimeError(
            f"{path}: the slipload command line is needed to compare against; build it with "
            "`cargo build --release -p slipload` or run `bash scripts/test.sh`"
        )
    return path


def run_cli(*args, cwd=None, check=True):
    out = subprocess.run(
        [str(cli_path()), *map(str, args)],
        cwd=cwd or ROOT,
        capture_output=True,
        text=True,
    )
    if check and out.returncode != 0:
        raise AssertionError(f"slipload {' '.join(map(str, args))} failed:\n{out.stderr}")
    return out


def cli_json(*args, cwd=None):
    return json.loads(run_cli(*args, cwd=cwd).stdout)


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def cli():
    return run_cli

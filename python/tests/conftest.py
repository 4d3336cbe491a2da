"""Shared helpers of the Python package's tests."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

import mpdem

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"


def shipped(name: str, end: float | None = None) -> mpdem.Scene:
    """A shipped scene, its run cut to `end` seconds when given."""
    scene = mpdem.Scene.from_file(SCENES / f"{name}.ron")
    if end is not None:
        scene.set("time.end", end)
    return scene


@pytest.fixture(scope="session")
def cli() -> Path:
    """The `mpdem` command line program, built in release if missing."""
    path = Path(os.environ.get("MPDEM_CLI", ROOT / "target" / "release" / "mpdem"))
    if not path.exists():
        subprocess.run(
            ["cargo", "build", "--release", "-p", "mpdem-cli"], cwd=ROOT, check=True
        )
    return path

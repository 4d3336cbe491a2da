"""Shared helpers of the Python package's tests."""

from __future__ import annotations

import os
import signal
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


@pytest.fixture
def ctrl_c_raises():
    """Ctrl-C raising KeyboardInterrupt, as in an interactive session, also
    when the tests were started with SIGINT ignored (a shell's background
    job starts so, and Python then installs no handler)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)

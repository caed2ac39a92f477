"""Shared fixtures: the repository's curves and the `immerse` binary."""

import os
import pathlib
import random

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CURVES = ROOT / "curves"


def binary():
    """The command-line tool: $IMMERSE_BIN, else the release build."""
    path = os.environ.get("IMMERSE_BIN") or str(ROOT / "target" / "release" / "immerse")
    if not os.access(path, os.X_OK):
        raise RuntimeError(
            f"the immerse binary is not at {path}: run 'cargo build --release' "
            "or set IMMERSE_BIN (scripts/python-test.sh does)"
        )
    return path


@pytest.fixture(scope="session")
def immerse_bin():
    return binary()


def star(rng, n, centre=(0.0, 0.0), radius=1.0):
    """A random star-shaped polygon (simple, counter-clockwise): self-overlapping."""
    angles = np.sort(rng.uniform(0.0, 2.0 * np.pi, n))
    # Distinct angles keep it a star around the centre.
    angles = angles + np.arange(n) * 1e-6
    radii = radius * rng.uniform(0.4, 1.0, n)
    return np.column_stack(
        [centre[0] + radii * np.cos(angles), centre[1] + radii * np.sin(angles)]
    )


@pytest.fixture
def rng():
    return np.random.default_rng(20260427)


@pytest.fixture
def pyrng():
    return random.Random(20260427)

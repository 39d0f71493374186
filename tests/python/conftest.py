# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Fixtures: the source tree, the CLI of the same build, Exp 2, the Python consensus laws."""

import os
import sys
import tomllib
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("MJF_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "examples/python"))  # consensus_law.py: the laws under test


@pytest.fixture(scope="session")
def source() -> Path:
    return SOURCE


@pytest.fixture(scope="session")
def cli() -> str:
    path = os.environ.get("MJF_CLI", str(SOURCE / "build/runner/mjformation"))
    assert Path(path).is_file(), f"the mjformation executable of this build: {path}"
    return path


@pytest.fixture(scope="session")
def exp2(source) -> Path:
    return source / "experiments/exp2.toml"


@pytest.fixture(scope="session")
def exp2_shape(exp2) -> dict:
    return tomllib.loads(exp2.read_text())["formation"]["shape"]


def short(duration: float) -> dict:
    """Overrides for a shortened run (its metric window and snapshots inside it)."""
    return {"run.duration": duration, "run.metric_window": [0.0, duration],
            "render.snapshots": []}

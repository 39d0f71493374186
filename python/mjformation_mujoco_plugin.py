# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Loads mjformation's native MuJoCo plugins (libmjformation_mujoco.so, docs/PLUGINS.md) into the
engine of the `mujoco` package: the entry point `mujoco.plugins` of a pip-installed mjformation,
which `import mujoco` calls. A module of its own, beside the package, so that importing mujoco
does not import mjformation."""

import ctypes
from pathlib import Path

LIBRARY = Path(__file__).resolve().parent / "mjformation" / "lib" / "libmjformation_mujoco.so"
_HANDLES = []


def load() -> None:
    """Loads the library once; its constructor registers the plugins with the engine."""
    if not _HANDLES:
        _HANDLES.append(ctypes.CDLL(str(LIBRARY)))

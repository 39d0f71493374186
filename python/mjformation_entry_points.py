# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The entry points of a pip-installed mjformation (pyproject.toml), in a module of their own
beside the package, so that neither imports mjformation (its engine, numpy, the runner library):

- `command`: the `mjformation` command, the runner executable the package carries
  (site-packages/mjformation/bin/mjformation) run in this process's place with the same
  arguments, so its exit codes, signals and output are the runner's own;
- `load_mujoco_plugins`: the `mujoco.plugins` entry point that `import mujoco` calls: loads
  libmjformation_mujoco.so, whose constructor registers our native MuJoCo plugins with the
  engine (docs/PLUGINS.md).
"""

import ctypes
import os
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent / "mjformation"
RUNNER = PACKAGE / "bin" / "mjformation"
NATIVE_PLUGINS = PACKAGE / "lib" / "libmjformation_mujoco.so"
_HANDLES = []


def command() -> None:
    if not RUNNER.is_file():
        sys.exit(f"mjformation: the runner executable is missing from the package: {RUNNER}")
    os.execv(str(RUNNER), [str(RUNNER), *sys.argv[1:]])


def load_mujoco_plugins() -> None:
    if not _HANDLES:
        _HANDLES.append(ctypes.CDLL(str(NATIVE_PLUGINS)))

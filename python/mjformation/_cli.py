# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The `mjformation` command of a pip-installed package: the runner executable the package
carries (site-packages/mjformation/bin/mjformation), run in this process's place with the same
arguments, so its exit codes, signals and output are the runner's own."""

import os
import sys
from pathlib import Path

RUNNER = Path(__file__).resolve().parent / "bin" / "mjformation"


def main() -> None:
    if not RUNNER.is_file():
        sys.exit(f"mjformation: the runner executable is missing from the package: {RUNNER}")
    os.execv(str(RUNNER), [str(RUNNER), *sys.argv[1:]])

#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The paper's figures for one run directory.

Usage: /usr/bin/python3 analysis/figures.py RUN_DIR [--out DIR]   (default DIR: RUN_DIR/figures)
"""

import argparse
import sys
from pathlib import Path

from mjfanalysis import plots
from mjfanalysis.io import load_run


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("run_dir", type=Path, help="a run directory written by `mjformation run`")
    ap.add_argument("--out", type=Path, default=None, help="output folder (RUN_DIR/figures)")
    args = ap.parse_args(argv)
    if not args.run_dir.is_dir():
        print(f"figures.py: {args.run_dir}: not a directory", file=sys.stderr)
        return 2
    run = load_run(args.run_dir)
    if run.timeseries is None:
        print(f"figures.py: {args.run_dir}: {run.ts_error}", file=sys.stderr)
        return 1
    if not run.complete:
        print(f"figures.py: warning: {run.name} is {run.status}: {run.error}", file=sys.stderr)
    marked = plots.marked_events(run)
    if run.event_count:
        print(f"figures.py: {run.name}: {run.event_count} safety events; {len(marked)} marked "
              "in red in the figures (flips, impacts, collisions, region exits)", file=sys.stderr)
    out = args.out or args.run_dir / "figures"
    for key, path in plots.run_figures(run, out).items():
        print(f"{key}: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

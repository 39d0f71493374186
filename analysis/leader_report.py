#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The "Non-cooperative leader" section alone: RESULTS_DIR/report/leaders.md.

Usage: /usr/bin/python3 analysis/leader_report.py RESULTS_DIR [--out DIR]
(RESULTS_DIR holds leaders/ and period_sweep/ from scripts/leader_study.sh; the main report
analysis/report.py includes the same section when they are present.)
Exit status: 0 when written, 2 when RESULTS_DIR holds neither folder.
"""

import argparse
import sys
from pathlib import Path

from mjfanalysis.leaders import write_section


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("results_dir", type=Path)
    ap.add_argument("--out", type=Path, default=None, help="report folder (RESULTS_DIR/report)")
    args = ap.parse_args(argv)
    try:
        path = write_section(args.results_dir, args.out or args.results_dir / "report")
    except FileNotFoundError as e:
        print(f"leader_report.py: {e}", file=sys.stderr)
        return 2
    print(f"leader_report.py: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

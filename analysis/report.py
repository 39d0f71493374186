#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Table 1 beside the paper's, the figures of every run and a discussion, as Markdown.

Usage: /usr/bin/python3 analysis/report.py RESULTS_DIR [--out DIR]   (default RESULTS_DIR/report)
Exit status: 0 when the report was written, 2 when RESULTS_DIR holds no run directory.
"""

import argparse
import sys
from pathlib import Path

from mjfanalysis.report import write_report


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("results_dir", type=Path, help="folder with one run directory per variant")
    ap.add_argument("--out", type=Path, default=None, help="report folder (RESULTS_DIR/report)")
    args = ap.parse_args(argv)
    out = args.out or args.results_dir / "report"
    try:
        path = write_report(args.results_dir, out)
    except FileNotFoundError as e:
        print(f"report.py: {e}", file=sys.stderr)
        return 2
    print(f"report.py: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The sweep plot of a `mjformation sweep --seeds` folder: a metric against the varied parameter,
mean and 95 % CI per cell, one line per value of the other varied parameters; runs with a flip,
ground impact or collision left out and counted, near misses and region exits kept (--all-runs:
every complete run).

Usage: /usr/bin/python3 analysis/sweep_plot.py SWEEP_DIR [--metric sigma_f_mean] [--x KEY]
       [--all-runs] [--logy] [--out PNG]   (default PNG: SWEEP_DIR/sweep_plot_<metric>.png)
Prints the plotted numbers as a Markdown table and the command that regenerates them.
"""

import argparse
import shlex
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from mjfanalysis import load_sweep  # noqa: E402
from mjfanalysis.sweep_plot import (left_out_reason, markdown_table, plot_sweep,  # noqa: E402
                                    sweep_lines)


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("sweep_dir", type=Path, help="a folder written by `mjformation sweep --seeds`")
    ap.add_argument("--metric", default="sigma_f_mean", help="a summary.json metric")
    ap.add_argument("--x", default=None, help="the varied key on the x axis (default: the first)")
    ap.add_argument("--all-runs", action="store_true",
                    help="statistics over every complete run, with a flip, ground impact or "
                         "collision or not")
    ap.add_argument("--logy", action="store_true", help="logarithmic metric axis")
    ap.add_argument("--out", type=Path, default=None, help="the PNG to write")
    return ap.parse_args(argv)


def main(argv=None) -> int:
    args = parse(argv)
    try:
        sweep = load_sweep(args.sweep_dir)
        x, lines = sweep_lines(sweep, args.metric, args.x, not args.all_runs)
    except (OSError, ValueError) as e:
        print(f"sweep_plot.py: {e}", file=sys.stderr)
        return 2
    ax = plot_sweep(sweep, args.metric, x=x, valid_only=not args.all_runs)
    if args.logy:
        ax.set_yscale("log")
    out = args.out or args.sweep_dir / f"sweep_plot_{args.metric}.png"
    ax.figure.tight_layout()
    ax.figure.savefig(out, dpi=110, metadata={"Software": None})
    plt.close(ax.figure)
    print(markdown_table(x, lines, args.metric,
                         "" if args.all_runs else left_out_reason(sweep)))
    print(f"\nfigure: {out}")
    print("regenerate: /usr/bin/python3 analysis/sweep_plot.py " +
          shlex.join(sys.argv[1:] if argv is None else argv))
    return 0


if __name__ == "__main__":
    sys.exit(main())

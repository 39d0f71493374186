#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The formation-tracking benchmark (docs/BENCHMARK.md): laws x scenarios x seeds, the board.

Usually started as `mjformation benchmark ...`, which passes its own path as --mjformation and
puts analysis/ on PYTHONPATH (analysis/README.md).
  mjformation benchmark [--laws a,b] [--scenarios x,y] [--seeds N] [--out DIR]
  mjformation benchmark --law NAME [--plugin-path DIR]   # NAME's row beside the stored board
  mjformation benchmark --law FILE.py:NAME               # a Python law's row (docs/PYTHON.md)
"""

import argparse
import math
import shlex
import sys
from pathlib import Path

from mjfanalysis import benchmark as b


def positive_int(text: str) -> int:
    """argparse type: an integer of at least 1 (argparse names the option in its error)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"takes a whole number of at least 1, not '{text}'")
    if value < 1:
        raise argparse.ArgumentTypeError(f"takes a whole number of at least 1, not {value}")
    return value


def positive_float(text: str) -> float:
    """argparse type: a finite number above 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"takes a number above 0, not '{text}'")
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"takes a number above 0, not {text}")
    return value


def parse(argv):
    p = argparse.ArgumentParser(prog="mjformation benchmark", description=__doc__.splitlines()[0])
    p.add_argument("--laws", help="comma-separated laws of experiments/benchmark/laws.toml "
                   "(default: all)")
    p.add_argument("--scenarios", help="comma-separated scenarios of experiments/benchmark/ "
                   "(default: all)")
    p.add_argument("--seeds", type=positive_int, default=3,
                   help="seeds per cell: run.seed = 1..N (N >= 1)")
    p.add_argument("--out", help="output folder (default runs/benchmark, with --law "
                   "runs/benchmark_<NAME>); cells done there before are skipped. A folder "
                   f"that exists must be a benchmark's (it holds {b.MARKER}) or empty")
    p.add_argument("--overwrite", action="store_true",
                   help="write the board into an existing --out that is not a benchmark's "
                   "(its leaderboard.md, .json and .png are replaced; nothing else is touched)")
    p.add_argument("--law", help="fly this one law on every scenario and print its row beside "
                   "the stored board (experiments/benchmark/leaderboard.json)")
    p.add_argument("--baseline", default=str(b.BASELINE),
                   help="the stored board --law is placed on (default: %(default)s)")
    p.add_argument("--set", dest="sets", action="append", default=[],
                   help="an override for every run, as mjformation run --set (repeat)")
    p.add_argument("--plugin-path", action="append", default=[],
                   help="extra folder to search for plugins (a law of your own)")
    p.add_argument("--jobs", type=positive_int, default=2, help="runs at once (default 2)")
    p.add_argument("--band", type=positive_float, default=b.bm.DEFAULT_BAND_M,
                   help="reaching band b of the reaching time, m, above 0 (default 1)")
    p.add_argument("--mjformation", default="mjformation", help="the runner to fly with")
    return p.parse_args(argv)


def law_name(law: str) -> str:
    """The row's name: a plugin's name, or NAME of a Python law FILE.py:NAME."""
    return law.rpartition(":")[2] if b.python_law(law) else law


def plan_of(args, baseline_meta) -> b.Plan:
    known = b.known_laws()
    if args.law:
        if b.python_law(args.law):
            laws = {law_name(args.law): str(Path(args.law).resolve())}
        else:
            laws = {args.law: known.get(args.law, f'{{plugin="{args.law}"}}')}
        # The stored board's seeds and overrides, so that the new row is comparable.
        seeds = baseline_meta.get("seeds") or list(range(1, args.seeds + 1))
        sets = args.sets or baseline_meta.get("sets") or []
        out = Path(args.out or f"runs/benchmark_{law_name(args.law)}")
    else:
        laws = {n: known[n] for n in b.pick(args.laws, known, "law")}
        seeds, sets, out = list(range(1, args.seeds + 1)), args.sets, Path(args.out or
                                                                          "runs/benchmark")
    return b.Plan(mjformation=args.mjformation, laws=laws,
                  scenarios=b.pick(args.scenarios, b.known_scenarios(), "scenario"),
                  seeds=seeds, out=out, sets=sets, plugin_path=args.plugin_path,
                  jobs=args.jobs, band=args.band)


def main(argv):
    args = parse(argv)
    stored, stored_meta = b.baseline_records(args.baseline) if args.law else ([], {})
    plan = plan_of(args, stored_meta)
    b.claim_out(plan.out, args.overwrite)
    records = b.fly_all(plan)
    info = b.meta(plan, [shlex.quote(a) for a in argv if a != "--mjformation"
                         and a != args.mjformation])
    if args.law:
        info["baseline"] = stored_meta
        records = [r for r in stored if r["law"] != law_name(args.law)] + records
        if not stored:
            print(f"benchmark: no stored board ({args.baseline}): the row below stands alone",
                  file=sys.stderr)
        else:
            print(f"Stored board {args.baseline}: benchmark version {stored_meta['benchmark_version']}, "
                  f"{stored_meta['date']}, {stored_meta['mjformation']}")
    b.write_board(records, info, plan.out)
    print((plan.out / "leaderboard.md").read_text())
    print(f"benchmark: board in {plan.out}/leaderboard.md, .json and .png", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

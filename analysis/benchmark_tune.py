#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Runs the benchmark's tuning procedure (docs/BENCHMARK.md) for the non-paper laws and prints
each law's chosen [formation] table, to be frozen in experiments/benchmark/laws.toml.

  /usr/bin/python3 analysis/benchmark_tune.py --mjformation build/runner/mjformation \\
      [--laws a,b] [--out runs/benchmark_tuning] [--jobs 2]
Writes <out>/<law>/tuning.json (every point and its score) and <out>/tuning.json (the choice).
"""

import argparse
import json
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mjfanalysis import benchmark_tuning as bt  # noqa: E402


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mjformation", default="mjformation")
    p.add_argument("--laws", help="comma-separated (default: every law of the search space)")
    p.add_argument("--out", default="runs/benchmark_tuning")
    p.add_argument("--jobs", type=int, default=2, help="laws tuned at once")
    p.add_argument("--points", type=int, default=bt.Budget.points)
    p.add_argument("--steps", type=int, default=bt.Budget.steps)
    p.add_argument("--set", dest="sets", action="append", default=[])
    args = p.parse_args(argv)
    laws = args.laws.split(",") if args.laws else list(bt.SEARCH_SPACE)
    budget = bt.Budget(points=args.points, steps=args.steps)
    out = Path(args.out)
    start = time.monotonic()

    def one(law):
        result = bt.tune_law(args.mjformation, law, out / law, budget, jobs=1, sets=args.sets)
        bt.write_result(result, out / law / "tuning.json")
        print(f"{law}: {result['runs']} runs, best score {result['best']['score']:.4g} m: "
              f"formation = '{result['formation']}'", flush=True)
        return result

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(one, laws))
    summary = {"budget": vars(budget), "scenario": str(bt.TUNING_SCENARIO.relative_to(bt.REPO)),
               "wall_s": round(time.monotonic() - start, 1),
               "laws": {r["law"]: {"formation": r["formation"], "score": r["best"]["score"],
                                   "runs": r["runs"]} for r in results}}
    (out / "tuning.json").write_text(json.dumps(summary, indent=1) + "\n")
    print(f"tuning: {sum(r['runs'] for r in results)} runs in {summary['wall_s']} s wall")
    return 0


if __name__ == "__main__":
    sys.exit(main())

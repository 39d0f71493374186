# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""A Monte Carlo sweep into pandas: Exp 2 on the ideal point mass, followers' start positions
jittered by up to 0.5 m per seed, mean sigma_f against the sample period T (Theorem 2: O(T)),
95 % confidence interval over the seeds.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/monte_carlo.py [--seeds 5]
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import mjformation  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default="runs/exp2_mc_py")
    parser.add_argument("--figure", default="exp2_mc_sigma_f.png")
    args = parser.parse_args()
    periods = [0.02, 0.05, 0.1, 0.2]
    sweep = mjformation.sweep(
        ROOT / "experiments/exp2.toml", vary={"formation.period": periods}, seeds=args.seeds,
        jobs=args.jobs, out=args.out, overwrite=True,
        set={"vehicles.model": "pointmass", "attitude": {"plugin": "pointmass_direct"},
             "vehicles.start_jitter": 0.5})
    table = sweep.frame()  # one row per cell: mean, std, 95 % CI of every metric
    cols = ["formation.period", "complete_runs", "sigma_f_mean_mean", "sigma_f_mean_ci95_low",
            "sigma_f_mean_ci95_high"]
    print(table[cols].to_string(index=False))
    runs = sweep.frame(runs=True)  # one row per run
    print(f"{len(runs)} runs, {int(runs['complete'].sum())} complete")
    ax = sweep.plot("sigma_f_mean", x="formation.period")  # mean, 95 % CI, and every run
    ax.set(xlabel="sample period T [s]", ylabel="mean sigma_f on [25, 40] s [m]",
           title="Exp 2, ideal point mass, start jittered 0.5 m")
    fig = ax.figure
    fig.tight_layout()
    fig.savefig(args.figure, dpi=120)
    print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()

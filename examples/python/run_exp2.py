# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Run Exp 2 from Python and plot sigma_f (eq. (68)) against time.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/run_exp2.py [--out runs/exp2_py]
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import mjformation  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="runs/exp2_py", help="run directory")
    parser.add_argument("--figure", default="exp2_sigma_f.png")
    args = parser.parse_args()
    run = mjformation.run(ROOT / "experiments/exp2.toml", out=args.out, overwrite=True)
    m = run.summary["metrics"]
    print(f"{run.summary['experiment']}: complete = {run.complete}, mean sigma_f on "
          f"{m['sigma_f_window']} s = {m['sigma_f_mean']:.4f} (paper's Table 1: 1.4405), "
          f"{run.summary['timing']['real_time_factor']:.0f}x real time")
    ts = run.timeseries  # {column: numpy array}
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.semilogy(ts["t"], ts["sigma_f"], lw=1)
    lo, hi = m["sigma_f_window"]
    ax.axvspan(lo, hi, color="0.9", label=f"metric window: mean {m['sigma_f_mean']:.3f}")
    ax.set(xlabel="t [s]", ylabel="sigma_f [m] (68)", title="Exp 2: discrete SMC (48), T = 0.05 s")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.figure, dpi=120)
    print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()

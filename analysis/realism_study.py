#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Table and figure of the sensor-noise x wind study (scripts/study_realism.sh).

Reads <study>/<exp>/sweep.json (mjformation sweep --seeds) and prints a Markdown table of the
mean sigma_f over the runs' metric window (summary.json metrics.sigma_f_window) with its 95 %
confidence interval (Student t over the seeds that
completed) per noise level and mean wind; a cell where runs stopped early (diverged) says how
many completed.
Usage: realism_study.py <study folder> [--figure out.png]
"""
import argparse
import re
from pathlib import Path

from mjfanalysis import load_run, load_sweep, window_label


def noise_label(value):
    if "ideal" in value:
        return "ideal"
    scale = re.search(r"scale\s*=\s*([0-9.]+)", value)
    return f"{float(scale.group(1)):g}x typical" if scale else "typical"


def wind_speed(value):
    mean = re.search(r"mean\s*=\s*\[\s*([-0-9.]+)", value)
    return float(mean.group(1)) if mean else 0.0


def load(folder):
    """(complete, {(noise, wind speed): cell}, the runs' metric window) of one sweep."""
    sweep = load_sweep(folder)
    finished = {}
    for run in sweep.runs:
        key = (noise_label(run["sensors"]), wind_speed(run["wind"]))
        finished[key] = finished.get(key, 0) + bool(run["finished"])
    cells = {}
    for cell in sweep.cells:
        key = (noise_label(cell["sensors"]), wind_speed(cell["wind"]))
        m = cell["metrics"].get("sigma_f_mean", {"n": 0, "mean": None, "ci95": [None, None]})
        cells[key] = {"mean": m["mean"], "ci": m["ci95"], "n": cell["complete_runs"],
                      "finished": finished.get(key, 0), "seeds": cell["seeds"]}
    return sweep.complete, cells, sweep.metric_window


def fmt(c):
    if c["finished"] == 0:
        return "not run"
    if c["n"] == 0 or c["mean"] is None:
        return f"all {c['finished']} runs stopped early"
    text = f"{c['mean']:.3g}"
    if c["ci"][0] is not None:
        text += f" [{c['ci'][0]:.3g}, {c['ci'][1]:.3g}]"
    if c["n"] < c["finished"]:
        text += f" ({c['finished'] - c['n']} of {c['finished']} stopped early)"
    if c["finished"] < c["seeds"]:
        text += f" ({c['seeds'] - c['finished']} not run)"
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("study", type=Path)
    parser.add_argument("--figure", type=Path)
    parser.add_argument("--bands", type=Path,
                        help="also draw sigma_f(t): median and 5-95 %% band over seeds")
    args = parser.parse_args()
    results = {}
    for folder in sorted(p for p in args.study.iterdir() if (p / "sweep.json").exists()):
        results[folder.name] = load(folder)
    noises = ["ideal", "typical", "3x typical"]
    for name, (complete, cells, window) in results.items():
        winds = sorted({w for _, w in cells})
        print(f"\n{name}: mean sigma_f on {window_label(window)}, 95 % CI"
              + ("" if complete else " (SWEEP INCOMPLETE)"))
        print("| sensors | " + " | ".join(f"wind {w:g} m/s" for w in winds) + " |")
        print("|---|" + "---|" * len(winds))
        for noise in noises:
            row = [fmt(cells[(noise, w)]) if (noise, w) in cells else "-" for w in winds]
            print(f"| {noise} | " + " | ".join(row) + " |")
    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        cols = min(2, len(results))
        rows = (len(results) + cols - 1) // cols
        fig, axes = plt.subplots(rows, cols, figsize=(6 * cols, 4 * rows), squeeze=False)
        for ax, (name, (_, cells, window)) in zip(axes.flat, results.items()):
            for noise, marker in zip(noises, "osd"):
                pts = sorted((w, c) for (n, w), c in cells.items() if n == noise and c["n"] > 0)
                if not pts:
                    continue
                w = [p[0] for p in pts]
                mean = [p[1]["mean"] for p in pts]
                low = [p[1]["mean"] - (p[1]["ci"][0] if p[1]["ci"][0] is not None else p[1]["mean"])
                       for p in pts]
                high = [(p[1]["ci"][1] if p[1]["ci"][1] is not None else p[1]["mean"]) - p[1]["mean"]
                        for p in pts]
                ax.errorbar(w, mean, yerr=[low, high], marker=marker, capsize=3, label=noise)
            ax.set_yscale("log")
            ax.set_xlabel("mean wind (m/s), moderate Dryden turbulence")
            ax.set_ylabel(f"mean sigma_f on {window_label(window)}")
            ax.set_title(f"{name}: mean and 95 % CI over seeds")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend()
        fig.tight_layout()
        args.figure.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.figure, dpi=110)
        print(f"\nfigure: {args.figure}")
    if args.bands:
        draw_bands(args.study, results, args.bands)


def sigma_f_series(run_dir):
    ts = load_run(run_dir).timeseries
    if ts is None:
        return None
    return ts["t"], ts["sigma_f"]


def draw_bands(study, results, out):
    """sigma_f(t) per cell: median and 5-95 % band over the seeds (runs that stopped early are
    left out of the band)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    noises = ["ideal", "typical", "3x typical"]
    fig, axes = plt.subplots(len(results), 3, figsize=(15, 3.6 * len(results)), squeeze=False,
                             sharey=True)
    for row, name in enumerate(results):
        sweep = load_sweep(study / name)
        groups = {}
        for run in sweep.runs:
            if run["complete"]:
                key = (noise_label(run["sensors"]), wind_speed(run["wind"]))
                groups.setdefault(key, []).append(run["run"])
        for col, noise in enumerate(noises):
            ax = axes[row][col]
            for wind in sorted({w for n, w in groups if n == noise}):
                series = [sigma_f_series(study / name / r) for r in groups[(noise, wind)]]
                series = [s for s in series if s is not None]
                if not series:
                    continue
                t = series[0][0]
                values = np.array([s[1][: len(t)] for s in series if len(s[1]) >= len(t)])
                median = np.median(values, axis=0)
                lo, hi = np.percentile(values, [5, 95], axis=0)
                line, = ax.plot(t, median, label=f"wind {wind:g} m/s ({len(values)} seeds)")
                ax.fill_between(t, lo, hi, color=line.get_color(), alpha=0.2)
            ax.set_yscale("log")
            ax.set_title(f"{name}, sensors {noise}")
            ax.set_xlabel("t (s)")
            ax.grid(True, which="both", alpha=0.3)
            if col == 0:
                ax.set_ylabel("sigma_f: median, 5-95 % band")
            ax.legend(fontsize=7)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)
    print(f"figure: {out}")


if __name__ == "__main__":
    main()

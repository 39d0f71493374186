#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Table of the timing study (scripts/study_timing.sh, issue 19).

Reads <study>/<exp>/{central,per_agent}/sweep.json and, per experiment, writes the mean sigma_f
(95 % CI, Student t over the completed runs, as the sweep computes it) per coupling x predict x
latency, and the largest latency of the grid up to which the formation holds (every run
completes and the mean sigma_f stays within 1.5x central mode's at this and every smaller
latency) beside the delay margin summary.json predicts (network.delay_margin).
Usage: timing_study.py <study folder> [--table out.md]
"""
import argparse
import re
from pathlib import Path

from mjfanalysis import load_sweep

EXPERIMENTS = ["exp2", "exp3"]


def label(value):
    """execution={...coupling="jacobi",jacobi_rounds=3,predict="input"} -> jacobi_m3, input."""
    coupling = re.search(r'coupling\s*=\s*"([a-z_]+)"', value).group(1)
    if coupling == "jacobi":
        coupling = "jacobi_m" + re.search(r"jacobi_rounds\s*=\s*([0-9]+)", value).group(1)
    return coupling, re.search(r'predict\s*=\s*"([a-z]+)"', value).group(1)


def sigma(cell):
    m = cell["metrics"].get("sigma_f_mean")
    if cell["complete_runs"] < cell["seeds"] or not m or m.get("mean") is None:
        return None
    low, high = m["ci95"]
    return m["mean"], (high - low) / 2


def margin(sweep):
    """network.delay_margin of the first run (by folder name) whose summary.json gives it."""
    for run in sorted(sweep.load_runs(), key=lambda r: r.name):
        net = (run.summary or {}).get("network", {})
        if "delay_margin" in net:
            return net["delay_margin"]
    return {}


def tables(study):
    lines = []
    for exp in EXPERIMENTS:
        central = load_sweep(study / exp / "central").cells[0]
        ref = sigma(central)
        grid = load_sweep(study / exp / "per_agent")
        dm = margin(grid)
        rows = {}
        for cell in grid.cells:
            key = label(cell["execution"])
            rows.setdefault(key, []).append((float(cell["network.latency"]), sigma(cell)))
        lats = sorted({lat for r in rows.values() for lat, _ in r})
        lines.append(f"\n### {exp} (point mass), central mode sigma_f = {ref[0]:.4g} ± {ref[1]:.2g} m")
        lines.append(f"\nPredicted margin: {1e3 * dm.get('without_prediction_s', float('nan')):.3g} ms "
                     f"without prediction, {1e3 * dm.get('with_prediction_s', float('nan')):.3g} ms with "
                     f"(rho(L_H^-1 A) = {dm.get('coupling_spectral_radius', float('nan')):.3g}).\n")
        lines.append("| coupling | predict | largest latency within 1.5x central | predicted margin | "
                     + " | ".join(f"{1e3 * l:g} ms" for l in lats) + " |")
        lines.append("|---|---|---|---|" + "---|" * len(lats))
        for (coupling, predict), cells in sorted(rows.items()):
            by_lat = dict(cells)
            holds = None
            for lat in lats:
                s = by_lat.get(lat)
                if s is None or s[0] > 1.5 * ref[0]:
                    break
                holds = lat
            held = "fails at 0 ms" if holds is None else f"{1e3 * holds:g} ms"
            pm = dm.get("with_prediction_s" if predict != "none" else "without_prediction_s")
            pm_text = f"< {1e3 * pm:.3g} ms" if pm is not None and coupling == "central_solve" else "n/a (Jacobi)"
            vals = []
            for lat in lats:
                s = by_lat.get(lat)
                vals.append("diverged" if s is None else f"{s[0]:.3g} ± {s[1]:.1g}")
            lines.append(f"| {coupling} | {predict} | {held} | {pm_text} | " + " | ".join(vals) + " |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("study", type=Path)
    parser.add_argument("--table", type=Path, default=Path("docs/timing_study_table.md"))
    args = parser.parse_args()
    text = ("# Timing study (issue 19): latency x prediction x coupling, point mass\n\n"
            "Regenerate: `bash scripts/study_timing.sh [seeds]` (this table: see the seeds per "
            "cell in the sweep). Mean sigma_f over the metric window, ± half the 95 % CI; "
            "'diverged': some run of the cell stopped early.\n" + tables(args.study))
    args.table.write_text(text)
    print(text)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Table of the timing study (scripts/study_timing.sh).

Reads <study>/<vehicle>/<exp>/{central,<part>}/sweep.json (PARTS below) and, per vehicle,
experiment and part, writes the mean sigma_f
(95 % CI, Student t over the completed runs, as the sweep computes it) per coupling x predict x
loss x latency, and the largest latency of the grid up to which the formation holds (every run
completes and the mean sigma_f stays within 1.5x central mode's at this and every smaller
latency) beside the delay margin summary.json predicts (network.delay_margin).
Usage: timing_study.py <study folder> [--table out.md]
"""
import argparse
import re
from pathlib import Path

from mjfanalysis import load_sweep

EXPERIMENTS = ["exp2", "exp3"]
VEHICLES = ["pointmass", "quadrotor"]
PARTS = {
    "in_phase": "a message every step, clocks in phase, no loss",
    "rates": "clocks in phase, the central solve, broadcast 20 / 50 / 100 Hz, loss 0 / 20 %",
    "off_phase": "a 50 Hz broadcast, follower clocks offset by U[0, T/2]",
    "off_phase_solve": "the central solve over the links, follower clocks offset by U[0, T/2]",
    "rates_couplings": "clocks in phase, no loss, broadcast 20 / 50 / 100 Hz, last_input and "
                       "Jacobi with the vehicle's prediction",
    "off_phase_sync": "as off_phase (loss 0), the clocks synchronised (clock_sync = true): "
                      "sampling out of phase, time stamps and prediction on the common time",
    "off_phase_solve_sync": "as off_phase_solve, the clocks synchronised (clock_sync = true)",
}
# The broadcast rate the script sets for a part that does not vary it.
DEFAULT_RATE = {"off_phase": 50.0, "off_phase_sync": 50.0}


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


def largest_holding(by_lat, lats, ref):
    """The largest latency up to which every cell completes within 1.5x central (None: not 0)."""
    holds = None
    for lat in lats:
        s = by_lat.get(lat)
        if s is None or s[0] > 1.5 * ref:
            break
        holds = lat
    return holds


def part_table(grid, ref, dm, lines, default_rate, in_phase):
    rows = {}
    for cell in grid.cells:
        coupling, predict = label(cell["execution"])
        loss = float(cell.get("network.loss", 0.0))
        rate = float(cell.get("network.rate", default_rate))
        rows.setdefault((coupling, predict, loss, rate), []).append(
            (float(cell["network.latency"]), sigma(cell)))
    lats = sorted({lat for r in rows.values() for lat, _ in r})
    lines.append("| coupling | predict | loss | broadcast | largest latency within 1.5x central | predicted margin | "
                 + " | ".join(f"{1e3 * l:g} ms" for l in lats) + " |")
    lines.append("|---|---|---|---|---|---|" + "---|" * len(lats))
    for (coupling, predict, loss, rate), cells in sorted(rows.items()):
        by_lat = dict(cells)
        holds = largest_holding(by_lat, lats, ref)
        held = "fails at 0 ms" if holds is None else f"{1e3 * holds:g} ms"
        pm = dm.get("with_prediction_s" if predict != "none" else "without_prediction_s")
        pm_text = (f"< {1e3 * pm:.3g} ms" if pm is not None and coupling == "central_solve"
                   and in_phase else "n/a")
        vals = ["diverged" if by_lat.get(lat) is None
                else f"{by_lat[lat][0]:.3g} ± {by_lat[lat][1]:.1g}" for lat in lats]
        lines.append(f"| {coupling} | {predict} | {100 * loss:g} % | {rate:g} Hz | {held} | {pm_text} | "
                     + " | ".join(vals) + " |")


def tables(study):
    lines = []
    for vehicle in VEHICLES:
        for exp in EXPERIMENTS:
            folder = study / vehicle / exp
            if not (folder / "central" / "sweep.json").exists():
                continue
            ref = sigma(load_sweep(folder / "central").cells[0])
            lines.append(f"\n## {exp}, {vehicle}: central mode sigma_f = {ref[0]:.4g} ± {ref[1]:.2g} m")
            for part, what in PARTS.items():
                if not (folder / part / "sweep.json").exists():
                    continue
                grid = load_sweep(folder / part)
                dm = margin(grid)
                lines.append(f"\n### {part}: {what}\n")
                if dm and part == "in_phase":
                    lines.append(
                        f"Predicted margin (central solve): "
                        f"{1e3 * dm.get('without_prediction_s', float('nan')):.3g} ms without "
                        f"prediction, {1e3 * dm.get('with_prediction_s', float('nan')):.3g} ms with "
                        f"(rho(L_H^-1 A) = {dm.get('coupling_spectral_radius', float('nan')):.3g}).\n")
                part_table(grid, ref[0], dm, lines, DEFAULT_RATE.get(part, 1000.0),
                           part == "in_phase")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("study", type=Path)
    parser.add_argument("--table", type=Path, default=Path("docs/timing_study_table.md"))
    args = parser.parse_args()
    text = ("# Timing study (issue 19): latency x prediction x coupling x clocks, point mass "
            "and quadrotor\n\n"
            "Regenerate: `bash scripts/study_timing.sh [seeds]` (this table: see the seeds per "
            "cell in the sweep). Mean sigma_f over the metric window, ± half the 95 % CI; "
            "'diverged': some run of the cell stopped early.\n" + tables(args.study))
    args.table.write_text(text)
    print(text)


if __name__ == "__main__":
    main()

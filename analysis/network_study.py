#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Exp 2 over a simulated network (issue 10): mean sigma_f against latency x loss, per-agent
execution (last received u_j, Jacobi m = 1 and 3, central solve) against central mode, over
seeds, with 95 % confidence intervals (Student t over the completed runs).

Run:  /usr/bin/python3 analysis/network_study.py build/runner/mjformation runs/network_study
Writes <out>/study.csv, <out>/study.md (the table in docs/RESULTS.md) and
docs/img/network_sigma_f.png.
"""
import csv
import math
import os
import subprocess
import sys

LATENCIES = [0.0, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1]  # s
LOSSES = [0.0, 0.05, 0.2, 0.5]
SEEDS = list(range(1, 11))
MODES = {
    "last_input": 'execution={mode="per_agent", coupling="last_input"}',
    "jacobi_m1": 'execution={mode="per_agent", coupling="jacobi", jacobi_rounds=1}',
    "jacobi_m3": 'execution={mode="per_agent", coupling="jacobi", jacobi_rounds=3}',
    "central_solve": 'execution={mode="per_agent", coupling="central_solve"}',
}
POINT_MASS = ['vehicles.model="pointmass"', 'attitude={plugin="pointmass_direct"}']
# Two-sided 95 % Student t quantiles by degrees of freedom.
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306,
       9: 2.262, 10: 2.228, 11: 2.201, 12: 2.179, 13: 2.160, 14: 2.145, 15: 2.131}


def sweep(binary, out, sets, varies):
    cmd = [binary, "sweep", "experiments/exp2.toml", "--no-render", "--overwrite", "-j", "2",
           "-o", out]
    for s in sets:
        cmd += ["--set", s]
    for v in varies:
        cmd += ["--vary", v]
    subprocess.run(cmd, check=False, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "sweep.csv")) as f:
        return list(csv.DictReader(f))


def mean_ci(values):
    n = len(values)
    if n == 0:
        return float("nan"), float("nan")
    m = sum(values) / n
    if n == 1:
        return m, 0.0
    sd = math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1))
    return m, T95.get(n - 1, 1.96) * sd / math.sqrt(n)


def main():
    binary, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    if binary == "--plot-only":  # redraw from <out>/study.csv
        with open(os.path.join(out, "study.csv")) as f:
            rows = [[r[0], float(r[1]) if r[1] != "-" else "-", float(r[2]) if r[2] != "-"
                     else "-", int(r[3]), int(r[4]), float(r[5]), float(r[6])]
                    for r in list(csv.reader(f))[1:]]
        write_table(rows, os.path.join(out, "study.md"))
        plot(rows, "docs/img/network_sigma_f.png")
        return
    rows = []
    central = sweep(binary, os.path.join(out, "central"), POINT_MASS,
                    ["run.seed=" + ",".join(map(str, SEEDS))])
    values = [float(r["sigma_f_mean"]) for r in central if r["complete"] == "true"]
    m, ci = mean_ci(values)
    rows.append(["central", "-", "-", len(central), len(values), m, ci])
    for mode, setting in MODES.items():
        runs = sweep(binary, os.path.join(out, mode), POINT_MASS + [setting], [
            "network.latency=" + ",".join(map(str, LATENCIES)),
            "network.loss=" + ",".join(map(str, LOSSES)),
            "run.seed=" + ",".join(map(str, SEEDS))])
        for lat in LATENCIES:
            for loss in LOSSES:
                cell = [r for r in runs if float(r["network.latency"]) == lat and
                        float(r["network.loss"]) == loss]
                done = [float(r["sigma_f_mean"]) for r in cell if r["complete"] == "true"]
                m, ci = mean_ci(done)
                rows.append([mode, lat, loss, len(cell), len(done), m, ci])
    with open(os.path.join(out, "study.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["mode", "latency_s", "loss", "runs", "completed", "sigma_f_mean",
                    "ci95"])
        w.writerows(rows)
    write_table(rows, os.path.join(out, "study.md"))
    plot(rows, "docs/img/network_sigma_f.png")


def cell_text(row):
    runs, done, m, ci = row[3], row[4], row[5], row[6]
    if done == 0:
        return "diverged (0/%d)" % runs
    text = "%.3g ± %.2g" % (m, ci)
    return text if done == runs else text + " (%d/%d)" % (done, runs)


def write_table(rows, path):
    with open(path, "w") as f:
        f.write("| mode | latency | " + " | ".join("loss %g %%" % (100 * l) for l in LOSSES) +
                " |\n")
        f.write("|---|---|" + "---|" * len(LOSSES) + "\n")
        f.write("| central (ideal) | - | %s |%s\n" % (cell_text(rows[0]), " |" * (len(LOSSES) - 1)))
        for mode in MODES:
            for lat in LATENCIES:
                cells = [r for r in rows if r[0] == mode and r[1] == lat]
                f.write("| %s | %g ms | %s |\n" % (mode, 1000 * lat,
                                                    " | ".join(cell_text(c) for c in cells)))


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(LOSSES), figsize=(4 * len(LOSSES), 3.6), sharey=True)
    for ax, loss in zip(axes, LOSSES):
        for mode in MODES:
            pts = [r for r in rows if r[0] == mode and r[2] == loss and r[4] > 0]
            if pts:
                x = [1000 * r[1] + 0.5 for r in pts]  # +0.5 ms so 0 shows on a log axis
                ax.errorbar(x, [r[5] for r in pts], yerr=[r[6] for r in pts], marker="o",
                            capsize=3, label=mode)
        ax.axhline(rows[0][5], color="k", ls="--", lw=1, label="central (ideal)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title("loss %g %%" % (100 * loss))
        ax.set_xlabel("latency + 0.5 ms [ms]")
    axes[0].set_ylabel("mean sigma_f, t in [25, 40] s [m]")
    axes[0].legend(fontsize=7)
    fig.suptitle("Exp 2, point mass, per-agent over a network (mean over completed runs, 95 % CI;"
                 " missing points: every run diverged; last_input diverged everywhere)",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()

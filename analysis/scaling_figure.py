#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Scaling figure of docs/PERFORMANCE.md: steps/s and real-time factor against the number of
followers, bare MuJoCo (one model, one thread) beside the full pipeline at each thread count.

Reads the JSON of `mjformation bench ... --threads 1,2 --json FILE` and writes a PNG; prints the
figures as a Markdown table.
Usage: scaling_figure.py bench.json out.png [--note "machine quiet, load 0.3"]
"""
import argparse
import json
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    report = json.loads(open(path).read())
    bare = {}
    full = defaultdict(dict)  # threads -> followers -> row
    for row in report["points"]:
        n = row["followers"]
        bare[n] = row
        full[row.get("threads", 1)][n] = row
    return report, bare, full


def table(report, bare, full):
    threads = sorted(full)
    head = "| followers | bare steps/s | " + " | ".join(
        f"{t} thread{'s' if t > 1 else ''}: steps/s | RTF" for t in threads)
    head += " | speed-up |" if len(threads) > 1 else " |"
    print(head)
    print("|---:" * (2 + 2 * len(threads) + (len(threads) > 1)) + "|")
    for n in sorted(bare):
        b = bare[n]
        cells = [f"{n}", f"{b['steps'] / b['bare_wall_s']:,.0f}"]
        for t in threads:
            r = full[t][n]
            cells += [f"{r['steps'] / r['full_wall_s']:,.0f}", f"{r['real_time_factor_full']:.2f}"]
        if len(threads) > 1:
            cells.append(f"{full[threads[-1]][n]['speed_up']:.2f}")
        print("| " + " | ".join(cells) + " |")


def figure(report, bare, full, out, note):
    ns = sorted(bare)
    fig, (ax_s, ax_r) = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, label in ((ax_s, "steps", "steps/s"), (ax_r, "rtf", "real-time factor")):
        def value(row, wall):
            return row["steps"] / row[wall] if key == "steps" else report["duration_s"] / row[wall]
        ax.plot(ns, [value(bare[n], "bare_wall_s") for n in ns], "k--o", label="bare MuJoCo")
        for t in sorted(full):
            ax.plot(ns, [value(full[t][n], "full_wall_s") for n in ns], "-o",
                    label=f"full pipeline, {t} thread{'s' if t > 1 else ''}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("followers")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    for level in (1, 2):
        ax_r.axhline(level, color="grey", lw=0.8)
    ax_s.legend(fontsize=8)
    title = (f"{os.path.basename(report['experiment'])}, rotor model {report['rotor_model']}, "
             f"{report['timestep_s'] * 1e3:g} ms steps")
    fig.suptitle(title + (f"\n{note}" if note else ""), fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bench_json")
    parser.add_argument("out_png")
    parser.add_argument("--note", default="", help="second title line (e.g. the machine's load)")
    args = parser.parse_args()
    report, bare, full = load(args.bench_json)
    table(report, bare, full)
    figure(report, bare, full, args.out_png, args.note)


if __name__ == "__main__":
    main()

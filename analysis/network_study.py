#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Tables and figure of the distributed-execution study (scripts/study_network.sh).

Reads <study>/<vehicle>/<exp>/{central,per_agent}/sweep.json (mjformation sweep --seeds) and
writes, per vehicle and experiment, a Markdown table of the mean sigma_f over the runs' metric
window (summary.json metrics.sigma_f_window) and the
reaching time, each with its 95 % confidence interval (Student t over the runs that completed,
as the sweep computes it), per coupling x latency x loss, with central mode as the reference.
Usage: network_study.py <study folder> [--table out.md] [--figure out.png]
"""
import argparse
import re
from pathlib import Path

from mjfanalysis import load_sweep, window_label

COUPLINGS = ["last_input", "jacobi_m1", "jacobi_m3", "central_solve"]
VEHICLES = ["pointmass", "quadrotor"]
EXPERIMENTS = ["exp2", "exp3"]


def coupling_label(value):
    """execution={mode="per_agent",coupling="jacobi",jacobi_rounds=3} -> jacobi_m3."""
    coupling = re.search(r'coupling\s*=\s*"([a-z_]+)"', value)
    name = coupling.group(1) if coupling else "last_input"
    if name == "jacobi":
        rounds = re.search(r"jacobi_rounds\s*=\s*([0-9]+)", value)
        return f"jacobi_m{rounds.group(1) if rounds else 1}"
    return name


def metric(cell, key):
    m = cell["metrics"].get(key)
    if not m or m.get("n", 0) == 0 or m.get("mean") is None:
        return None
    low, high = m["ci95"]
    half = (high - low) / 2 if low is not None and high is not None else 0.0
    return {"n": m["n"], "mean": m["mean"], "ci": half}


def summarize(cell, finished):
    """One cell: how many runs finished, completed, reached, and the two metrics."""
    return {"seeds": cell["seeds"], "finished": finished, "complete": cell["complete_runs"],
            "sigma": metric(cell, "sigma_f_mean"), "reach": metric(cell, "reaching_time_s")}


def load(folder):
    """(complete, {(coupling, latency, loss): cell} of a per-agent sweep or {None: cell} of
    central mode, the runs' metric window)."""
    sweep = load_sweep(folder)

    def key(entry):
        if "execution" not in entry:
            return None
        return (coupling_label(entry["execution"]), float(entry["network.latency"]),
                float(entry["network.loss"]))

    finished = {}
    for run in sweep.runs:
        finished[key(run)] = finished.get(key(run), 0) + bool(run["finished"])
    cells = {key(c): summarize(c, finished.get(key(c), 0)) for c in sweep.cells}
    return sweep.complete, cells, sweep.metric_window


def cell_text(c):
    if c["finished"] == 0:
        return "not run"
    if c["complete"] == 0:
        text = f"diverged ({c['finished']}/{c['finished']})"
    else:
        s = c["sigma"]
        text = f"{s['mean']:.3g} ± {s['ci']:.2g}"
        r = c["reach"]
        if r is None:
            text += "; not reached"
        else:
            text += f"; t_r {r['mean']:.3g} ± {r['ci']:.2g} s"
            if r["n"] < c["complete"]:
                text += f" ({r['n']}/{c['complete']} reached)"
        if c["complete"] < c["finished"]:
            text += f" ({c['finished'] - c['complete']}/{c['finished']} diverged)"
    if c["finished"] < c["seeds"]:
        text += f" ({c['seeds'] - c['finished']} not run)"
    return text


def table(vehicle, exp, central, grid):
    latencies = sorted({k[1] for k in grid})
    losses = sorted({k[2] for k in grid})
    lines = [f"### {exp}, {vehicle}", "",
             "| coupling | latency | " + " | ".join(f"loss {100 * l:g} %" for l in losses) + " |",
             "|---|---|" + "---|" * len(losses)]
    if central is not None:
        lines.append(f"| central mode | - | {cell_text(central)} |" + " |" * (len(losses) - 1))
    for coupling in COUPLINGS:
        for lat in latencies:
            cells = [cell_text(grid[(coupling, lat, l)]) if (coupling, lat, l) in grid else "-"
                     for l in losses]
            if any(c != "-" for c in cells):
                lines.append(f"| {coupling} | {1000 * lat:g} ms | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def holds(cell, reference):
    """The formation holds: every run completed and the mean sigma_f is within 2x central mode."""
    return (cell["finished"] > 0 and cell["complete"] == cell["finished"]
            and cell["sigma"] is not None and cell["sigma"]["mean"] <= 2 * reference)


def breaking_table(results):
    """Per vehicle, experiment and coupling: up to which latency the formation holds, per loss."""
    lines = []
    for (vehicle, exp), (central, grid) in results.items():
        if central is None or central["sigma"] is None:
            continue
        reference = central["sigma"]["mean"]
        losses = sorted({k[2] for k in grid})
        latencies = sorted({k[1] for k in grid})
        if not lines:
            lines = ["| experiment | vehicle | central mode sigma_f (m) | coupling | "
                     + " | ".join(f"loss {100 * l:g} %" for l in losses) + " |",
                     "|---|---|---|---|" + "---|" * len(losses)]
        for coupling in COUPLINGS:
            cells = []
            for loss in losses:
                held = None
                for lat in latencies:
                    c = grid.get((coupling, lat, loss))
                    if c is None or not holds(c, reference):
                        break
                    held = lat
                if held is None:
                    cells.append("fails at 0 ms")
                elif held == latencies[-1]:
                    cells.append(f"holds to {1000 * held:g} ms (all)")
                else:
                    cells.append(f"holds to {1000 * held:g} ms")
            lines.append(f"| {exp} | {vehicle} | {reference:.3g} | {coupling} | "
                         + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot(results, path, window):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5), squeeze=False)
    colours = dict(zip(COUPLINGS, ["C0", "C1", "C2", "C3"]))
    for ax, ((vehicle, exp), (central, grid)) in zip(axes.flat, results.items()):
        for coupling in COUPLINGS:
            for loss, style in ((0.0, "-"), (0.2, "--")):
                pts = sorted((k[1], c) for k, c in grid.items()
                             if k[0] == coupling and k[2] == loss and c["sigma"] is not None)
                if not pts:
                    continue
                x = [1000 * p[0] + 0.5 for p in pts]  # + 0.5 ms: 0 ms shows on a log axis
                mean = [p[1]["sigma"]["mean"] for p in pts]
                ci = [p[1]["sigma"]["ci"] for p in pts]
                # A lower bound at or below 0 cannot be drawn on the log axis: cut at 1 %.
                low = [min(c, 0.99 * m) for m, c in zip(mean, ci)]
                ax.errorbar(x, mean, yerr=[low, ci], color=colours[coupling],
                            ls=style, marker="o", ms=3, capsize=2,
                            label=f"{coupling}, loss {100 * loss:g} %")
        if central is not None and central["sigma"] is not None:
            ax.axhline(central["sigma"]["mean"], color="k", ls=":", lw=1.2, label="central mode")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{exp}, {vehicle}", fontsize=10)
        ax.set_xlabel("latency + 0.5 ms (ms)")
        ax.set_ylabel(f"mean sigma_f on {window} (m)")
        ax.grid(True, which="both", alpha=0.3)
    handles = {}  # one legend for all panels: a coupling may have no point in some panel
    for ax in axes.flat:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    order = [f"{c}, loss {l} %" for c in COUPLINGS for l in ("0", "20")] + ["central mode"]
    labels = [label for label in order if label in handles]
    fig.legend([handles[label] for label in labels], labels, loc="lower center", ncol=5,
               fontsize=8)
    fig.suptitle("Per-agent smc_discrete over a network: mean over completed runs, 95 % CI "
                 "(missing points: every run diverged)", fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 0.97))
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("study", type=Path)
    parser.add_argument("--table", type=Path, help="write the tables to this Markdown file")
    parser.add_argument("--figure", type=Path)
    args = parser.parse_args()
    results, text, windows = {}, [], []
    for vehicle in VEHICLES:
        for exp in EXPERIMENTS:
            folder = args.study / vehicle / exp
            if not (folder / "per_agent" / "sweep.json").exists():
                continue
            complete, grid, window = load(folder / "per_agent")
            windows.append(window)
            central = None
            if (folder / "central" / "sweep.json").exists():
                central_complete, cells, window = load(folder / "central")
                windows.append(window)
                central = cells.get(None)
                complete = complete and central_complete
            results[(vehicle, exp)] = (central, grid)
            text.append(table(vehicle, exp, central, grid)
                        + ("" if complete else "\n(SWEEP INCOMPLETE)\n"))
    if not results:
        parser.error(f"{args.study}: no <vehicle>/<exp>/per_agent/sweep.json found")
    known = {w for w in windows if w is not None}
    window = window_label(known.pop() if len(known) == 1 else None)
    body = ("### Where the protocol breaks\n\nThe largest latency up to which the formation holds "
            "(every run completes and the mean sigma_f stays within 2x central mode's, at this "
            "and every smaller latency of the grid):\n\n" + breaking_table(results) + "\n"
            + "\n".join(text))
    print(body)
    if args.table:
        args.table.write_text(
            "<!-- Generated by analysis/network_study.py from scripts/study_network.sh; do not "
            "edit. -->\n# Distributed-execution study: every cell\n\nMean sigma_f on "
            f"{window} ± 95 % CI (m); t_r: reaching time ± 95 % CI over the runs that reached the band. "
            "See docs/RESULTS.md.\n\n" + body)
    if args.figure:
        plot(results, args.figure, window)
        print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The benchmark's board from per-run records (docs/BENCHMARK.md, "The board"): per (law,
scenario) cell the mean score over seeds with its 95 % interval and a rank; an overall rank from
the normalised score; leaderboard.json, leaderboard.md and the heat map.

A record is {"law", "scenario", "seed", "metrics"}, metrics as benchmark_metrics.run_metrics
writes them. Lower scores are better. A cell with any failed seed is failed: it gets no number
and no rank (a crash is not a large error). A cell whose law cannot fly the scenario (a
per-agent scenario, a law without a per-agent version) is not applicable: no number, no rank,
not a failure, and left out of the law's overall score. Ranks: 1 + the number of laws whose interval lies
entirely below this law's; two laws whose intervals overlap are never ranked apart, and a rank
shared with another law is a tie (written "2=").
"""

from __future__ import annotations

import json
import math

import numpy as np

SCORE = "rms_slot_error_m"
METRIC_COLUMNS = ("sigma_f_mean", "rms_slot_error_m", "reaching_time_s", "chattering_index",
                  "control_effort", "min_separation_m", "messages_per_s")
# t_{0.975, df}, df = 1..30 (as runner/app/src/sweep_stats.cc; any statistics table).
T975 = (12.7062, 4.3027, 3.1824, 2.7764, 2.5706, 2.4469, 2.3646, 2.3060, 2.2622, 2.2281, 2.2010,
        2.1788, 2.1604, 2.1448, 2.1314, 2.1199, 2.1098, 2.1009, 2.0930, 2.0860, 2.0796, 2.0739,
        2.0687, 2.0639, 2.0595, 2.0555, 2.0518, 2.0484, 2.0452, 2.0423)


def interval95(samples) -> tuple[float, float, float]:
    """(mean, low, high): Student-t 95 % interval of the mean, cut at 0 for non-negative
    samples; with one sample low = high = mean (no interval can be stated)."""
    x = np.asarray(samples, dtype=float)
    mean = float(np.mean(x))
    if len(x) < 2:
        return mean, mean, mean
    t = T975[len(x) - 2] if len(x) <= 31 else 1.96  # normal quantile beyond df = 30
    half = t * float(np.std(x, ddof=1)) / math.sqrt(len(x))
    # Scores are never negative: a low end below zero says only "near zero" (as sweep_stats.cc).
    low = max(mean - half, 0.0) if np.all(x >= 0) else mean - half
    return mean, low, mean + half


def rank_by_interval(entries: dict) -> dict:
    """{name: (mean, low, high)} -> {name: (rank, tied)}: rank = 1 + number of others whose high
    is below this low; tied when another name has the same rank."""
    ranks = {n: 1 + sum(o[2] < e[1] for m, o in entries.items() if m != n)
             for n, e in entries.items()}
    return {n: (r, sum(r == q for q in ranks.values()) > 1) for n, r in ranks.items()}


def _cell(law: str, scenario: str, recs: list, score: str) -> dict:
    """One cell: per-seed scores, mean, interval, failure and the means of every metric."""
    recs = sorted(recs, key=lambda r: r["seed"])
    failed = [f"seed {r['seed']}: {r['metrics']['failed']}" for r in recs if r["metrics"]["failed"]]
    cell = {"law": law, "scenario": scenario, "seeds": [r["seed"] for r in recs],
            "failed": "; ".join(failed) or None, "per_seed": None, "mean": None, "ci95": None,
            "rank": None, "tie": False, "normalised": None, "metrics_mean": {},
            "not_applicable": next((r["metrics"]["not_applicable"] for r in recs
                                    if r["metrics"].get("not_applicable")), None)}
    if failed or cell["not_applicable"]:
        return cell
    cell["per_seed"] = [r["metrics"][score] for r in recs]
    mean, lo, hi = interval95(cell["per_seed"])
    cell.update(mean=mean, ci95=[lo, hi])
    for key in METRIC_COLUMNS:
        vals = [r["metrics"].get(key) for r in recs]
        finite = [v for v in vals if v is not None and math.isfinite(v)]
        cell["metrics_mean"][key] = float(np.mean(finite)) if len(finite) == len(vals) else None
    return cell


def scored(cell: dict) -> bool:
    """The cell has a number: neither failed nor not applicable."""
    return not cell["failed"] and not cell.get("not_applicable")


def _rank_scenario(cells: list) -> None:
    """Ranks and normalised scores (mean / best mean) of one scenario's cells, in place."""
    ok = [c for c in cells if scored(c)]
    if not ok:
        return
    best = min(c["mean"] for c in ok)
    ranks = rank_by_interval({c["law"]: (c["mean"], *c["ci95"]) for c in ok})
    for c in ok:
        c["rank"], c["tie"] = ranks[c["law"]]
        c["normalised"] = c["mean"] / best if best > 0 else (1.0 if c["mean"] == 0 else math.inf)


def _overall(law: str, cells: list, best: dict) -> dict:
    """A law's overall score: per seed, the mean over the scenarios it applies to of score / the
    scenario's best mean; its mean and interval over seeds. None when any of its cells failed,
    and when it was not flown on every scenario or with the same seeds on each (not
    comparable)."""
    failed = [c["scenario"] for c in cells if c["failed"]]
    not_applicable = [c["scenario"] for c in cells if c.get("not_applicable")]
    row = {"law": law, "failed_cells": failed, "not_applicable": not_applicable, "mean": None,
           "ci95": None, "rank": None, "tie": False}
    if failed or len(cells) < len(best) or len({tuple(c["seeds"]) for c in cells}) != 1 or \
            len(not_applicable) == len(cells):
        return row
    per_seed = np.mean([np.asarray(c["per_seed"]) / best[c["scenario"]] for c in cells
                        if scored(c)], axis=0)
    mean, lo, hi = interval95(per_seed)
    row.update(mean=mean, ci95=[lo, hi])
    return row


def build(records: list, score: str = SCORE) -> dict:
    """The board: {"laws", "scenarios", "cells", "overall"} from per-run records. Laws and
    scenarios keep the order of first appearance; overall rows are in rank order, the laws
    with failed cells last (fewest failures first)."""
    laws = list(dict.fromkeys(r["law"] for r in records))
    scenarios = list(dict.fromkeys(r["scenario"] for r in records))
    groups: dict = {}
    for r in records:
        groups.setdefault((r["law"], r["scenario"]), []).append(r)
    cells = [_cell(law, s, groups[(law, s)], score) for law in laws for s in scenarios
             if (law, s) in groups]
    best = {}
    for s in scenarios:
        col = [c for c in cells if c["scenario"] == s]
        _rank_scenario(col)
        ok = [c["mean"] for c in col if scored(c)]
        best[s] = min(ok) if ok and min(ok) > 0 else math.nan
    overall = [_overall(law, [c for c in cells if c["law"] == law], best) for law in laws]
    ok = {o["law"]: (o["mean"], *o["ci95"]) for o in overall if o["mean"] is not None
          and math.isfinite(o["mean"])}
    for o in overall:
        if o["law"] in ok:
            o["rank"], o["tie"] = rank_by_interval(ok)[o["law"]]
    overall.sort(key=lambda o: (o["rank"] is None, len(o["failed_cells"]), o["mean"] or 0.0))
    return {"score": score, "laws": laws, "scenarios": scenarios, "cells": cells,
            "overall": overall}


def _finite(v):
    """v with every non-finite float replaced by None (JSON has no NaN or infinity)."""
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_finite(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def write_json(board: dict, path, meta: dict, records: list) -> None:
    """leaderboard.json: meta (version, date, seeds, ...), the board and the per-run records
    (so that a later `benchmark --law` can rank a new law among these)."""
    with open(path, "w") as f:
        json.dump(_finite(dict(meta, **board, runs=records)), f, indent=1, allow_nan=False)
        f.write("\n")


def _fmt(v, digits=3) -> str:
    return "n/a" if v is None or not math.isfinite(v) else f"{v:.{digits}g}"


def _rank_text(rank, tie) -> str:
    return "" if rank is None else f"#{rank}{'=' if tie else ''}"


def cell_text(c: dict) -> str:
    """'0.83 [0.80, 0.86] #2=', 'FAILED (reason)' or 'not applicable (reason)'."""
    if c.get("not_applicable"):
        return "not applicable (" + c["not_applicable"] + ")"
    if c["failed"]:
        return "**FAILED** (" + c["failed"].replace("|", "/") + ")"
    lo, hi = c["ci95"]
    interval = f" [{_fmt(lo)}, {_fmt(hi)}]" if len(c["seeds"]) > 1 else ""
    return f"{_fmt(c['mean'])}{interval} {_rank_text(c['rank'], c['tie'])}"


def overall_text(o: dict) -> str:
    if o["failed_cells"]:
        return f"**FAILED** in {len(o['failed_cells'])} scenario(s)"
    if o["mean"] is None:
        return "n/a (not every scenario, or other seeds)"
    lo, hi = o["ci95"]
    interval = f" [{_fmt(lo)}, {_fmt(hi)}]" if lo != hi else ""
    skipped = len(o.get("not_applicable", []))
    without = f" (without {skipped} not applicable)" if skipped else ""
    return f"{_fmt(o['mean'])}{interval} {_rank_text(o['rank'], o['tie'])}{without}"


def board_table(board: dict) -> list[str]:
    """The Markdown board: one row per law (overall rank order), one column per scenario."""
    cells = {(c["law"], c["scenario"]): c for c in board["cells"]}
    head = "| law | overall (normalised) | " + " | ".join(f"`{s}`" for s in board["scenarios"])
    lines = [head + " |", "|---" * (2 + len(board["scenarios"])) + "|"]
    for o in board["overall"]:
        row = [cell_text(cells[(o["law"], s)]) if (o["law"], s) in cells else "not run"
               for s in board["scenarios"]]
        lines.append(f"| `{o['law']}` | {overall_text(o)} | " + " | ".join(row) + " |")
    return lines


def metrics_table(board: dict) -> list[str]:
    """Every metric's mean over seeds per cell (failed cells: the reason)."""
    lines = ["| law | scenario | " + " | ".join(METRIC_COLUMNS) + " |",
             "|---" * (2 + len(METRIC_COLUMNS)) + "|"]
    for c in board["cells"]:
        vals = (["FAILED"] * len(METRIC_COLUMNS) if c["failed"]
                else ["not applicable"] * len(METRIC_COLUMNS) if c.get("not_applicable")
                else [_fmt(c["metrics_mean"].get(k), 4) for k in METRIC_COLUMNS])
        lines.append(f"| `{c['law']}` | `{c['scenario']}` | " + " | ".join(vals) + " |")
    return lines


def markdown(board: dict, meta: dict) -> str:
    """leaderboard.md: what was run, the board, the metrics per cell."""
    seeds = meta.get("seeds", [])
    text = [f"# Formation-tracking benchmark board ({meta.get('date', '')})", "",
            f"Benchmark version {meta.get('benchmark_version')}, "
            f"{meta.get('mjformation')}; command: `{meta.get('command', '')}`.",
            f"Score: `{board['score']}` (lower is better; docs/BENCHMARK.md), mean over "
            f"{len(seeds)} seed(s) {seeds} with its 95 % Student-t interval; #k is the rank, "
            "'=' a tie (intervals overlap). Overall: the mean over scenarios of score / the "
            "scenario's best mean, per seed. A cell with a failed seed (flip, ground impact, "
            "collision, incomplete or non-finite run) is FAILED, not a number; a law without a "
            "per-agent version is not applicable to a per-agent scenario. messages_per_s: "
            "per-agent scenarios only."]
    if len(seeds) < 2:
        text.append("With one seed there is no interval: ranks order the means and no tie "
                    "can be called.")
    return "\n".join(text + ["", *board_table(board), "", "## Every metric (mean over seeds)",
                             "", *metrics_table(board), ""])


def heatmap(board: dict, path) -> None:
    """Laws x scenarios coloured by the normalised score (1 = the scenario's best, log colour
    scale up to 10x); failed cells grey, hatched and marked FAILED; cells not applicable white,
    marked n/a."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    laws = [o["law"] for o in board["overall"]]
    cells = {(c["law"], c["scenario"]): c for c in board["cells"]}
    grid = np.full((len(laws), len(board["scenarios"])), np.nan)
    fig, ax = plt.subplots(figsize=(1.6 + 1.3 * len(board["scenarios"]), 1.0 + 0.5 * len(laws)))
    for i, law in enumerate(laws):
        for j, s in enumerate(board["scenarios"]):
            c = cells.get((law, s))
            if c is None:
                continue
            if c.get("not_applicable"):
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="white",
                                           edgecolor="0.6"))
                ax.text(j, i, "n/a", ha="center", va="center", fontsize=8, color="0.3")
                continue
            if c["failed"]:
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="0.8",
                                           hatch="xx", edgecolor="0.45"))
                ax.text(j, i, "FAILED", ha="center", va="center", fontsize=8, color="0.1")
                continue
            grid[i, j] = c["normalised"]
            dark = np.log10(max(c["normalised"], 1.0)) > 0.5  # viridis_r's dark half
            ax.text(j, i, _fmt(c["normalised"], 3), ha="center", va="center", fontsize=8,
                    color="white" if dark else "black")
    image = ax.imshow(np.log10(np.clip(grid, 1.0, 10.0)), cmap="viridis_r", vmin=0.0, vmax=1.0,
                      aspect="auto")
    bar = fig.colorbar(image, ax=ax, ticks=[0.0, 0.5, 1.0])
    bar.ax.set_yticklabels(["1 (best)", "3.2", ">= 10"])
    bar.set_label("score / best in scenario")
    ax.set_xticks(range(len(board["scenarios"])), board["scenarios"], rotation=30, ha="right")
    ax.set_yticks(range(len(laws)), laws)
    ax.set_xlim(-0.5, len(board["scenarios"]) - 0.5)
    ax.set_ylim(len(laws) - 0.5, -0.5)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)

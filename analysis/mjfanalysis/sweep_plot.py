# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The sweep plot: a metric against the varied parameter of a `mjformation sweep --seeds`, per
grid cell the mean with its 95 % Student-t confidence interval (the runner's, sweep.json), one
line per value of the other varied parameters.

Runs with a safety event (summary.json "events") are left out by default and counted: the cell's
statistics are then sweep.json's `metrics_event_free` (the sweep.csv rows with `statistics_over =
event_free_runs`). A cell whose runs all gave the same value (std 0), or that has a single run,
has no interval: it is drawn as an open marker, never as a zero-width bar.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .varied import axis_value


@dataclass
class Point:
    """One grid cell on the plot: x value, mean and 95 % CI of the metric over `n` runs."""

    x: object
    mean: float
    low: float
    high: float
    n: int
    left_out: int  # complete runs with a safety event, not in the statistics
    runs: list = field(default_factory=list)  # the metric of each run in the statistics
    left_out_runs: list = field(default_factory=list)  # the metric of each run left out

    @property
    def has_interval(self) -> bool:
        """False for a constant (all runs equal) or a single run: nothing to draw as an interval."""
        return self.n >= 2 and _finite(self.low) and _finite(self.high) and self.high > self.low


@dataclass
class Line:
    """The cells that share the values of the other varied keys (`label`: "key=value, ...")."""

    label: str
    points: list = field(default_factory=list)

    @property
    def left_out(self) -> int:
        return sum(p.left_out for p in self.points)


def _finite(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _number(v) -> float:
    return float(v) if _finite(v) else math.nan


def _x_value(raw):
    """A varied value as a hashable x: a number or text (a list or table stays its TOML text)."""
    v = axis_value(raw)
    return v if isinstance(v, (int, float, str)) and not isinstance(v, bool) else str(raw)


def _text(v) -> str:
    v = _x_value(v)
    return f"{v:g}" if isinstance(v, float) else str(v)


def _cell_key(entry: dict, keys: list[str]) -> tuple:
    return tuple(str(entry.get(k)) for k in keys)


def _run_values(sweep, metric: str, keys: list[str], event_free: bool) -> dict:
    """{cell key: (metric of each run in the statistics, of each run left out, how many were
    left out)} from sweep.json's runs: the complete ones, without a safety event if event_free."""
    values = {}
    for entry in sweep.runs:
        kept, dropped, count = values.setdefault(_cell_key(entry, keys), ([], [], [0]))
        if not entry.get("complete"):
            continue
        v = (entry.get("metrics") or {}).get(metric)
        left_out = event_free and (entry.get("safety_events") or 0) > 0
        count[0] += left_out
        if _finite(v):
            (dropped if left_out else kept).append(float(v))
    return {k: (kept, dropped, count[0]) for k, (kept, dropped, count) in values.items()}


def _point(cell: dict, metric: str, x: str, runs: tuple, event_free: bool) -> Point:
    table = cell.get("metrics_event_free") if event_free else None
    stats = (table if table is not None else cell.get("metrics") or {}).get(metric) or {}
    low, high = (stats.get("ci95") or [None, None])[:2]
    kept, dropped, left_out = runs
    return Point(_x_value(cell.get(x)), _number(stats.get("mean")), _number(low),
                 _number(high), int(stats.get("n") or 0), left_out, kept, dropped)


def sweep_lines(sweep, metric: str = "sigma_f_mean", x: str | None = None,
                event_free: bool = True) -> tuple[str, list[Line]]:
    """(x, the lines) of the sweep plot of `sweep` (a mjfanalysis.io.Sweep: its path, varied,
    runs and cells are read; not imported here, so that io.py may import this module). Raises
    ValueError for a sweep without cells (no --seeds),
    one that varies nothing, an unknown x or a metric no cell has."""
    keys = sweep.varied
    if not sweep.cells:
        raise ValueError(f"{sweep.path}: no cells (a sweep with --seeds has them): no interval")
    if not keys:
        raise ValueError(f"{sweep.path}: the sweep varies no parameter: nothing to plot against")
    x = x or keys[0]
    if x not in keys:
        raise ValueError(f"{sweep.path}: '{x}' is not varied (varied: {', '.join(keys)})")
    known = sorted({m for c in sweep.cells for m in (c.get("metrics") or {})})
    if metric not in known:
        raise ValueError(f"{sweep.path}: no metric '{metric}' (metrics: {', '.join(known)})")
    others = [k for k in keys if k != x]
    runs = _run_values(sweep, metric, keys, event_free)
    lines = {}
    for cell in sweep.cells:
        label = ", ".join(f"{k}={_text(cell.get(k))}" for k in others)
        line = lines.setdefault(label, Line(label))
        line.points.append(_point(cell, metric, x, runs.get(_cell_key(cell, keys), ([], [], 0)),
                                  event_free))
    return x, list(lines.values())


def _positions(lines: list[Line]) -> tuple[dict, bool]:
    """{x value: plot position}: the values themselves when all are numbers, else 0, 1, ... in
    first-seen order (categorical, labelled with the values)."""
    values = [p.x for line in lines for p in line.points]
    if all(_finite(v) for v in values):
        return {v: float(v) for v in values}, True
    order = list(dict.fromkeys(str(v) for v in values))
    return {v: float(order.index(str(v))) for v in values}, False


def _draw_line(ax, line: Line, positions: dict, color, event_free: bool, dx: float) -> None:
    """The means joined, the 95 % CI bars (open markers where there is none), and beside them
    (dx to the right, not hidden by the bar) each run: dots, an x for each run left out."""
    pts = sorted(line.points, key=lambda p: positions[p.x])
    xs = [positions[p.x] for p in pts]
    label = line.label or "mean"
    if event_free and line.left_out:
        label += f" ({line.left_out} run(s) with safety events left out)"
    ax.plot(xs, [p.mean for p in pts], "-", color=color, label=label)
    for p, xp in zip(pts, xs):
        ax.plot([xp + dx] * len(p.runs), p.runs, ".", color=color, alpha=0.5, ms=4)
        ax.plot([xp + dx] * len(p.left_out_runs), p.left_out_runs, "x", color="grey", ms=6)
        if p.has_interval:
            ax.errorbar([xp], [p.mean], yerr=[[p.mean - p.low], [p.high - p.mean]], fmt="o",
                        color=color, capsize=4)
        else:
            ax.plot([xp], [p.mean], "o", mfc="white", color=color)


def plot_sweep(sweep, metric: str = "sigma_f_mean", x: str | None = None, ax=None,
               event_free: bool = True, title: str | None = None):
    """Draws the sweep plot on `ax` (a new figure when None) and returns the axes. event_free:
    leave out (and count) the runs with a safety event; False: every complete run."""
    import matplotlib.pyplot as plt

    x, lines = sweep_lines(sweep, metric, x, event_free)
    ax = ax or plt.subplots(figsize=(7.0, 4.2))[1]
    positions, numeric = _positions(lines)
    colors = plt.get_cmap("tab10")
    span = max(positions.values()) - min(positions.values())
    for i, line in enumerate(lines):
        _draw_line(ax, line, positions, colors(i % 10), event_free, 0.015 * (span or 1.0))
    if not numeric:
        ax.set_xticks(sorted(set(positions.values())),
                      list(dict.fromkeys(str(v) for v in positions)))
    if not all(p.has_interval for line in lines for p in line.points):
        ax.plot([], [], "o", mfc="white", color="grey", label="no interval (constant or one run)")
    left_out = sum(line.left_out for line in lines)
    if left_out:
        ax.plot([], [], "x", color="grey", label="run with a safety event (left out)")
    which = f"event-free runs ({left_out} with safety events left out)" if event_free else \
        "all complete runs (safety events or not)"
    ax.set(xlabel=x, ylabel=metric,
           title=title or f"{metric}: mean and 95 % CI per cell ({sweep.seeds} seeds)\n"
                          f"over the {which}; dots: the runs")
    ax.title.set_fontsize(9)
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8)
    return ax


def markdown_table(x: str, lines: list[Line], metric: str) -> str:
    """The plotted numbers: one row per cell (line, x, n, mean, 95 % CI, runs left out)."""
    rows = [f"| line | {x} | n | {metric} mean | 95 % CI | left out (safety events) |",
            "|---|---|---|---|---|---|"]
    for line in lines:
        for p in line.points:
            ci = f"[{p.low:.4g}, {p.high:.4g}]" if p.has_interval else "none (constant or one run)"
            rows.append(f"| {line.label or '-'} | {_text(p.x)} | {p.n} | {p.mean:.4g} | {ci} | "
                        f"{p.left_out} |")
    return "\n".join(rows)

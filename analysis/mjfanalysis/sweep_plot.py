# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The sweep plot: a metric against the varied parameter of a `mjformation sweep --seeds`, per
grid cell the mean with its 95 % Student-t confidence interval (the runner's, sweep.json), one
line per value of the other varied parameters.

Runs with an invalidating safety event (a flip, ground impact or collision: sweep.json's
`left_out_events`) are left out by default and counted; near misses and region exits are only
reported and the runs kept. The cell's statistics are then sweep.json's `metrics_valid` (the
sweep.csv rows with `statistics_over = valid_runs`). A sweep.json written before that distinction
(no `left_out_events`) left out every run with any event (`metrics_event_free`), and is read so,
and the caption says so. A cell whose runs all gave the same value (std 0), or that has a single
run, has no interval: it is drawn as an open marker, never as a zero-width bar.
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
    left_out: int  # complete runs with an invalidating event, not in the statistics
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


def _invalidating(entry: dict) -> int:
    """A run's flips, ground impacts and collisions; an older sweep.json (without the count)
    left out a run for any event."""
    if "invalidating_events" in entry:
        return int(entry.get("invalidating_events") or 0)
    return int(entry.get("safety_events") or 0)


def _run_values(sweep, metric: str, keys: list[str], valid_only: bool) -> dict:
    """{cell key: (metric of each run in the statistics, of each run left out, how many were
    left out)} from sweep.json's runs: the complete ones, without an invalidating event if
    valid_only."""
    values = {}
    for entry in sweep.runs:
        kept, dropped, count = values.setdefault(_cell_key(entry, keys), ([], [], [0]))
        if not entry.get("complete"):
            continue
        v = (entry.get("metrics") or {}).get(metric)
        left_out = valid_only and _invalidating(entry) > 0
        count[0] += left_out
        if _finite(v):
            (dropped if left_out else kept).append(float(v))
    return {k: (kept, dropped, count[0]) for k, (kept, dropped, count) in values.items()}


def _cells_from_runs(sweep, keys: list[str], valid_only: bool) -> list[dict]:
    """One cell per run of a sweep without --seeds: the run's metric as the mean of one run
    (none when the run did not complete or, with valid_only, had an invalidating event)."""
    cells = []
    for entry in sweep.runs:
        usable = bool(entry.get("complete")) and not (valid_only and _invalidating(entry) > 0)
        metrics = {name: {"n": int(usable and _finite(v)), "mean": v if usable else None}
                   for name, v in (entry.get("metrics") or {}).items()}
        cells.append({**{k: entry.get(k) for k in keys}, "metrics": metrics})
    return cells


def _point(cell: dict, metric: str, x: str, runs: tuple, valid_only: bool) -> Point:
    table = cell.get("metrics_valid", cell.get("metrics_event_free")) if valid_only else None
    stats = (table if table is not None else cell.get("metrics") or {}).get(metric) or {}
    low, high = (stats.get("ci95") or [None, None])[:2]
    kept, dropped, left_out = runs
    return Point(_x_value(cell.get(x)), _number(stats.get("mean")), _number(low),
                 _number(high), int(stats.get("n") or 0), left_out, kept, dropped)


def sweep_lines(sweep, metric: str = "sigma_f_mean", x: str | None = None,
                valid_only: bool = True) -> tuple[str, list[Line]]:
    """(x, the lines) of the sweep plot of `sweep` (a mjfanalysis.io.Sweep: its path, varied,
    runs and cells are read; not imported here, so that io.py may import this module). A sweep
    without --seeds has no cells: each run is then its own point (one run, no interval). Raises
    ValueError for a sweep that varies nothing, an unknown x or a metric no cell has."""
    keys = sweep.varied
    cells = sweep.cells or _cells_from_runs(sweep, keys, valid_only)
    if not keys:
        raise ValueError(f"{sweep.path}: the sweep varies no parameter: nothing to plot against")
    x = x or keys[0]
    if x not in keys:
        raise ValueError(f"{sweep.path}: '{x}' is not varied (varied: {', '.join(keys)})")
    known = sorted({m for c in cells for m in (c.get("metrics") or {})})
    if metric not in known:
        raise ValueError(f"{sweep.path}: no metric '{metric}' (metrics: {', '.join(known)})")
    others = [k for k in keys if k != x]
    runs = _run_values(sweep, metric, keys, valid_only)
    lines = {}
    for cell in cells:
        label = ", ".join(f"{k}={_text(cell.get(k))}" for k in others)
        line = lines.setdefault(label, Line(label))
        line.points.append(_point(cell, metric, x, runs.get(_cell_key(cell, keys), ([], [], 0)),
                                  valid_only))
    return x, list(lines.values())


def _positions(lines: list[Line]) -> tuple[dict, bool]:
    """{x value: plot position}: the values themselves when all are numbers, else 0, 1, ... in
    first-seen order (categorical, labelled with the values)."""
    values = [p.x for line in lines for p in line.points]
    if all(_finite(v) for v in values):
        return {v: float(v) for v in values}, True
    order = list(dict.fromkeys(str(v) for v in values))
    return {v: float(order.index(str(v))) for v in values}, False


def _draw_line(ax, line: Line, positions: dict, color, valid_only: bool, dx: float) -> None:
    """The means joined, the 95 % CI bars (open markers where there is none), and beside them
    (dx to the right, not hidden by the bar) each run: dots, an x for each run left out."""
    pts = sorted(line.points, key=lambda p: positions[p.x])
    xs = [positions[p.x] for p in pts]
    label = line.label or "mean"
    if valid_only and line.left_out:
        label += f" ({line.left_out} run(s) left out)"
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
               valid_only: bool = True, title: str | None = None):
    """Draws the sweep plot on `ax` (a new figure when None) and returns the axes. valid_only:
    leave out (and count) the runs with a flip, ground impact or collision; False: every
    complete run."""
    import matplotlib.pyplot as plt

    x, lines = sweep_lines(sweep, metric, x, valid_only)
    ax = ax or plt.subplots(figsize=(7.0, 4.2))[1]
    positions, numeric = _positions(lines)
    colors = plt.get_cmap("tab10")
    span = max(positions.values()) - min(positions.values())
    for i, line in enumerate(lines):
        _draw_line(ax, line, positions, colors(i % 10), valid_only, 0.015 * (span or 1.0))
    if not numeric:
        ax.set_xticks(sorted(set(positions.values())),
                      list(dict.fromkeys(str(v) for v in positions)))
    if not all(p.has_interval for line in lines for p in line.points if p.n > 0):
        ax.plot([], [], "o", mfc="white", color="grey", label="no interval (constant or one run)")
    left_out = sum(line.left_out for line in lines)
    if left_out:
        ax.plot([], [], "x", color="grey", label=f"run left out ({left_out_reason(sweep)})")
    which = f"valid runs ({left_out} left out: {left_out_reason(sweep)})" if valid_only else \
        "all complete runs (safety events or not)"
    ax.set(xlabel=x, ylabel=metric,
           title=title or _title(sweep, metric, which))
    ax.title.set_fontsize(9)
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8)
    return ax


def _title(sweep, metric: str, which: str) -> str:
    if not sweep.cells:
        return f"{metric}: one run per cell (no seeds: no interval)\nover the {which}"
    return f"{metric}: mean and 95 % CI per cell ({sweep.seeds} seeds)\nover the {which}; dots: the runs"


def left_out_reason(sweep) -> str:
    """Why runs leave the statistics: the kinds sweep.json names, or (an older sweep.json) any
    safety event."""
    kinds = sweep.table.get("left_out_events")
    if kinds is None:
        return "any safety event (a sweep.json from before near misses were kept)"
    names = [k.replace("_", " ") for k in kinds]
    return "a " + (", ".join(names[:-1]) + " or " + names[-1] if len(names) > 1 else names[0])


def markdown_table(x: str, lines: list[Line], metric: str, reason: str = "") -> str:
    """The plotted numbers: one row per cell (line, x, n, mean, 95 % CI, runs left out), and
    under them why runs were left out (`reason`, left_out_reason)."""
    rows = [f"| line | {x} | n | {metric} mean | 95 % CI | left out |",
            "|---|---|---|---|---|---|"]
    for line in lines:
        for p in line.points:
            ci = (f"[{p.low:.4g}, {p.high:.4g}]" if p.has_interval else
                  "none (no run left)" if p.n == 0 else "none (constant or one run)")
            rows.append(f"| {line.label or '-'} | {_text(p.x)} | {p.n} | {p.mean:.4g} | {ci} | "
                        f"{p.left_out} |")
    left_out = sum(line.left_out for line in lines)
    if left_out and reason:
        rows.append(f"\n{left_out} complete run(s) left out: {reason}.")
    return "\n".join(rows)

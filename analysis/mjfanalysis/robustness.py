# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The robustness map: experiment x tilt_max x attitude plugin, each at its default
gains, from the sweep folders that scripts/robustness_map.sh writes.

Layout read: MAP_DIR/<experiment>__<plugin>/sweep.json (written by `mjformation sweep`) and, per
run, MAP_DIR/<experiment>__<plugin>/<run>/{summary.json, timeseries.csv}, through the loader
(mjfanalysis.io).
"""

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .io import load_sweep, read_timeseries

REACHED_TOLERANCE_M = 1.0  # "formation reached": every follower within this of its slot at the end
TILT_MARGIN_DEG = 10.0     # the map's criterion: no vehicle beyond its tilt limit by more than this


@dataclass
class Cell:
    experiment: str
    plugin: str
    tilt_max: float
    complete: bool
    error: str
    sigma_f_mean: float = math.nan
    max_slot_error_m: float = math.nan
    rms_tilt_deg: list = None          # per follower, in the metric window
    tilt_hz: list = None               # per follower, dominant rocking frequency
    max_tilt_deg_window: float = math.nan
    max_tilt_deg_run: float = math.nan  # whole run, every follower, from timeseries.csv

    @property
    def refused(self) -> bool:
        return not self.complete and "refused its configuration" in (self.error or "")

    @property
    def reached(self) -> bool:
        return self.complete and self.max_slot_error_m < REACHED_TOLERANCE_M

    @property
    def rms_tilt_mean(self) -> float:
        v = [x for x in (self.rms_tilt_deg or []) if x is not None]
        return float(np.mean(v)) if v else math.nan

    @property
    def over_limit_deg(self) -> float:
        """How far the worst follower tilted beyond tilt_max over the whole run (deg)."""
        return self.max_tilt_deg_run - math.degrees(self.tilt_max)


def _num(text) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def max_tilt_from_timeseries(path: Path) -> float:
    """Largest follower tilt (deg) in timeseries.csv: acos(cos roll cos pitch) of every uav>=1."""
    ts = read_timeseries(path)
    worst = math.nan
    i = 1
    while f"uav{i}_roll" in ts:
        roll, pitch = ts[f"uav{i}_roll"], ts[f"uav{i}_pitch"]
        tilt = np.degrees(np.arccos(np.clip(np.cos(roll) * np.cos(pitch), -1, 1)))
        worst = np.nanmax([worst, np.nanmax(tilt)]) if math.isfinite(worst) else np.nanmax(tilt)
        i += 1
    return float(worst)


def _cell(entry: dict, run, experiment: str, plugin: str) -> Cell:
    cell = Cell(experiment, plugin, float(entry["attitude.tilt_max"]), bool(entry["complete"]),
                entry.get("error") or "")
    if cell.complete and run.summary is not None:
        m = run.summary.get("metrics") or {}
        cell.sigma_f_mean = _num(m.get("sigma_f_mean"))
        cell.max_slot_error_m = _num(m.get("max_final_slot_error_m"))
        cell.rms_tilt_deg = m.get("rms_tilt_deg_in_window")
        cell.tilt_hz = m.get("tilt_oscillation_hz_in_window")
        cell.max_tilt_deg_window = _num(m.get("max_follower_tilt_deg_in_window"))
    if cell.complete and (run.path / "timeseries.csv").exists():
        cell.max_tilt_deg_run = max_tilt_from_timeseries(run.path / "timeseries.csv")
    return cell


def read_sweep(folder: Path, experiment: str, plugin: str) -> list[Cell]:
    sweep = load_sweep(folder)
    return [_cell(entry, sweep.run(entry), experiment, plugin) for entry in sweep.runs]


def read_map(map_dir: Path) -> list[Cell]:
    cells = []
    for folder in sorted(p for p in Path(map_dir).iterdir() if (p / "sweep.json").exists()):
        experiment, _, plugin = folder.name.partition("__")
        cells += read_sweep(folder, experiment, plugin)
    return cells


def _f(x, digits=2) -> str:
    return f"{x:.{digits}f}" if isinstance(x, (int, float)) and math.isfinite(x) else "—"


def markdown(cells: list[Cell]) -> list[str]:
    """The map as Markdown lines: one table per experiment, rows tilt_max, column groups plugin."""
    lines = []
    plugins = list(dict.fromkeys(c.plugin for c in cells))
    for experiment in dict.fromkeys(c.experiment for c in cells):
        lines += [f"### `{experiment}`", "",
                  "| tilt_max (rad / deg) | plugin | reached | mean σ_f | max slot error at end (m) "
                  "| RMS tilt in window (deg, mean [min, max] of followers) | rocking (Hz) "
                  "| max tilt in window (deg) | max tilt whole run (deg) | beyond limit (deg) |",
                  "|---|---|---|---:|---:|---|---:|---:|---:|---:|"]
        rows = sorted((c for c in cells if c.experiment == experiment),
                      key=lambda c: (c.tilt_max, plugins.index(c.plugin)))
        for c in rows:
            head = f"{c.tilt_max:.2f} / {math.degrees(c.tilt_max):.0f}"
            if not c.complete:
                status = "refused" if c.refused else "failed"
                lines.append(f"| {head} | {c.plugin} | **{status}** | | | | | | | |")
                continue
            rms = [x for x in (c.rms_tilt_deg or []) if x is not None]
            hz = [x for x in (c.tilt_hz or []) if x is not None]
            rms_cell = (f"{np.mean(rms):.1f} [{min(rms):.1f}, {max(rms):.1f}]" if rms else "—")
            over = c.over_limit_deg
            lines.append("| " + " | ".join([
                head, c.plugin, "yes" if c.reached else "**no**", _f(c.sigma_f_mean, 3),
                _f(c.max_slot_error_m, 3), rms_cell,
                f"{np.median(hz):.2f}" if hz else "—", _f(c.max_tilt_deg_window, 1),
                _f(c.max_tilt_deg_run, 1),
                (f"**{over:+.1f}**" if over > TILT_MARGIN_DEG else f"{round(over, 1) or 0.0:+.1f}"),
            ]) + " |")
        lines.append("")
    return lines


def compact_markdown(cells: list[Cell]) -> list[str]:
    """One row per (experiment, tilt_max), one column per plugin:
    "reached? · mean sigma_f · RMS tilt (deg) · max tilt over the run (deg)"."""
    plugins = list(dict.fromkeys(c.plugin for c in cells))
    lines = ["| experiment | tilt_max (rad / deg) | " + " | ".join(f"`{p}`" for p in plugins) + " |",
             "|---|---|" + "---|" * len(plugins)]
    keys = sorted({(c.experiment, c.tilt_max) for c in cells})
    by = {(c.experiment, c.tilt_max, c.plugin): c for c in cells}
    for experiment, tilt in keys:
        row = [f"`{experiment}`", f"{tilt:.2f} / {math.degrees(tilt):.0f}"]
        for p in plugins:
            c = by.get((experiment, tilt, p))
            if c is None:
                row.append("")
            elif not c.complete:
                row.append("refused" if c.refused else "failed")
            else:
                reached = "**yes**" if c.reached else "no"
                over = c.over_limit_deg
                flag = f" (**{over:+.0f} over**)" if over > TILT_MARGIN_DEG else ""
                row.append(f"{reached} · {_f(c.sigma_f_mean, 2)} · {_f(c.rms_tilt_mean, 1)} · "
                           f"{_f(c.max_tilt_deg_run, 1)}{flag}")
        lines.append("| " + " | ".join(row) + " |")
    return lines


def write_csv(cells: list[Cell], path: Path) -> None:
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["experiment", "plugin", "tilt_max", "complete", "refused", "reached",
                    "sigma_f_mean", "max_slot_error_m", "rms_tilt_deg_mean", "max_tilt_deg_window",
                    "max_tilt_deg_run", "over_limit_deg"])
        for c in cells:
            w.writerow([c.experiment, c.plugin, c.tilt_max, c.complete, c.refused, c.reached,
                        c.sigma_f_mean, c.max_slot_error_m, c.rms_tilt_mean,
                        c.max_tilt_deg_window, c.max_tilt_deg_run, c.over_limit_deg])

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The one loader of run and sweep directories: timeseries.csv, summary.json, config.toml
(docs/ARCHITECTURE.md), sweep.json. Pure Python (numpy), so that mjfanalysis works alone; the
mjformation Python module returns these same Run and Sweep objects (docs/PYTHON.md) and, when it
is importable, lends timeseries.csv its C++ reader."""

from __future__ import annotations

import csv
import functools
import json
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .varied import axis_value  # noqa: F401  (re-exported: callers read it from here)

NAN = float("nan")


@functools.cache
def module_reader():
    """The runner's own timeseries reader (mjformation._core.read_csv) when the Python module is
    built or installed, else None. Looked up on first use, not at import: mjformation imports
    this module, so an import-time lookup would be circular."""
    try:
        from mjformation._core import read_csv
    except ImportError:
        return None
    return read_csv


def _cell(text: str) -> float:
    text = text.strip()
    if not text:
        return NAN  # empty cell: not applicable (e.g. sliding variables of a plain guidance law)
    try:
        return float(text)
    except ValueError:
        return NAN


def read_timeseries(path) -> dict[str, np.ndarray]:
    """timeseries.csv as {column name: float array}; empty cells become NaN.

    A run killed while writing may leave a truncated last line: rows whose number of cells does
    not match the header are dropped. With the mjformation Python module importable this is its
    C++ reader (docs/PYTHON.md; same arrays, tested), else the csv module below.
    """
    reader = module_reader()
    if reader is not None:
        header, data = reader(str(path))  # columns x rows
        return {name: data[j] for j, name in enumerate(header)}
    return read_timeseries_csv(path)


def read_timeseries_csv(path) -> dict[str, np.ndarray]:
    """read_timeseries in pure Python (the csv module)."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        try:
            header = [h.strip() for h in next(reader)]
        except StopIteration:
            raise ValueError(f"{path}: empty file (no header)") from None
        rows = [[_cell(c) for c in r] for r in reader if len(r) == len(header)]
    data = np.array(rows, dtype=float).reshape(len(rows), len(header))
    return {name: data[:, j].copy() for j, name in enumerate(header)}


def read_summary(path) -> dict:
    with open(path) as f:
        return json.load(f)


def read_config(path) -> dict:
    with open(path, "rb") as f:
        return tomllib.load(f)


@dataclass(repr=False)
class Run:
    """One run directory: summary (summary.json as a dict), config (config.toml), timeseries
    ({column: array}), frame() (pandas). `status` is "complete", "incomplete" (summary says
    complete = false) or "unfinished" (no summary.json: still running or killed). `result` is
    what mjformation.run returned for it (None when loaded from disk)."""

    path: Path
    summary: dict | None = None
    config: dict | None = None
    config_error: str | None = None
    _ts: dict | None = None
    ts_error: str | None = None
    result: dict | None = None

    def __repr__(self) -> str:
        return f"Run({str(self.path)!r}, status={self.status!r})"

    @property
    def name(self) -> str:
        return self.path.name

    @property
    def status(self) -> str:
        if self.summary is None:
            return "unfinished"
        return "complete" if self.summary.get("complete") is True else "incomplete"

    @property
    def complete(self) -> bool:
        return self.status == "complete"

    @property
    def error(self) -> str | None:
        if self.summary is None:
            return "no summary.json: the run is still going or was killed"
        return self.summary.get("error")

    @property
    def timeseries(self) -> dict | None:
        if self._ts is None and self.ts_error is None:
            p = self.path / "timeseries.csv"
            if not p.exists():
                self.ts_error = "no timeseries.csv"
            else:
                try:
                    self._ts = read_timeseries(p)
                    if "t" not in self._ts or len(self._ts["t"]) == 0:
                        self.ts_error = "timeseries.csv has no data rows"
                        self._ts = None
                except (OSError, ValueError) as e:
                    self.ts_error = str(e)
        return self._ts

    def frame(self):
        """The tidy long form (pandas): one row per (t, vehicle), columns t, vehicle (0 = the
        leader), sigma_f, then the per-vehicle columns without their `uav<i>_` prefix."""
        import pandas as pd

        ts = self.timeseries
        if ts is None:
            raise ValueError(f"{self.path}: {self.ts_error}")
        vehicles = sorted({int(k[3:].split("_")[0]) for k in ts if k.startswith("uav")})
        parts = []
        for v in vehicles:
            prefix = f"uav{v}_"
            cols = {k[len(prefix):]: ts[k] for k in ts if k.startswith(prefix)}
            parts.append(pd.DataFrame({"t": ts["t"], "vehicle": v, "sigma_f": ts["sigma_f"],
                                       **cols}))
        return pd.concat(parts, ignore_index=True)

    def metric(self, key: str) -> float:
        """summary.json metrics[key] as a float (NaN when absent or null)."""
        v = ((self.summary or {}).get("metrics") or {}).get(key)
        return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else NAN

    def plugin_report(self, key: str) -> float:
        v = ((self.summary or {}).get("plugin_report") or {}).get(key)
        return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else NAN

    @property
    def metric_window(self) -> tuple[float, float] | None:
        """The window [t0, t1] (s) the run's windowed metrics use (summary metrics
        sigma_f_window), or None when the summary does not say."""
        w = ((self.summary or {}).get("metrics") or {}).get("sigma_f_window")
        if isinstance(w, list) and len(w) == 2 and all(finite(x) for x in w):
            return float(w[0]), float(w[1])
        return None

    @property
    def vehicle_model(self) -> str:
        m = (self.summary or {}).get("vehicle_model")
        if not m and self.config:
            m = (self.config.get("vehicles") or {}).get("model")
        return str(m) if m else "?"

    @property
    def label(self) -> str:
        return (self.summary or {}).get("experiment") or self.name

    def snapshots(self) -> list[Path]:
        listed = (self.summary or {}).get("snapshots") or []
        found = [self.path / s for s in listed if (self.path / s).is_file()]
        for p in sorted((self.path / "snapshots").glob("*.png")):
            if p not in found:
                found.append(p)
        return sorted(found)

    @property
    def events(self) -> list[dict]:
        """summary.json events.list (safety events: kind, time_s, vehicles, value, what), in
        the order recorded; [] for an event-free run."""
        ev = (self.summary or {}).get("events") or {}
        return [e for e in (ev.get("list") or []) if isinstance(e, dict)]

    @property
    def event_count(self) -> int:
        ev = (self.summary or {}).get("events") or {}
        return int(ev.get("count", len(self.events)) or 0)

    @property
    def video(self) -> Path | None:
        p = self.path / "video.mp4"
        return p if p.is_file() else None


def load_run(path) -> Run:
    path = Path(path)
    run = Run(path=path)
    sp = path / "summary.json"
    if sp.is_file():
        try:
            run.summary = read_summary(sp)
        except (OSError, ValueError) as e:
            # A summary that cannot be read counts as a failed run, not as a result.
            run.summary = {"complete": False, "error": f"summary.json unreadable: {e}"}
    cp = path / "config.toml"
    if cp.is_file():
        try:
            run.config = read_config(cp)
        except (OSError, tomllib.TOMLDecodeError) as e:
            run.config_error = str(e)
    return run


def find_runs(results_dir) -> list[Run]:
    """Every sub-directory of results_dir that is a run directory (it holds summary.json, or a
    timeseries.csv of a run still going / killed)."""
    results_dir = Path(results_dir)
    runs = []
    if not results_dir.is_dir():
        return runs
    for d in sorted(results_dir.iterdir()):
        if d.is_dir() and ((d / "summary.json").is_file() or (d / "timeseries.csv").is_file()):
            runs.append(load_run(d))
    return runs


def finite(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


# What sweep.json says of every run besides its varied keys (runner/app/src/sweep_tables.cc).
_RUN_ENTRY_KEYS = ("seed", "complete", "finished", "run", "error", "safety_events",
                   "first_safety_event", "invalidating_events", "metrics")


class Sweep:
    """One sweep directory (mjformation sweep, the CLI's or mjformation.sweep's): sweep.json as
    written. `runs`: one dict per run (the varied keys, seed, complete, finished, run = its
    folder, error, safety_events, metrics); `cells` (with --seeds): one dict per grid cell, whose
    `metrics[key]` holds n, mean, std, ci95 over the cell's complete runs and, when some run had a
    safety event, `metrics_valid[key]` the same over the runs without a flip, ground impact or
    collision (`left_out_events`; a sweep.json from before: `metrics_event_free`, over the runs
    without any event)."""

    def __init__(self, path, table: dict):
        self.path = Path(path)
        self.table = table

    def __repr__(self) -> str:
        return f"Sweep({str(self.path)!r}, runs={len(self.runs)}, complete={self.complete})"

    complete = property(lambda self: bool(self.table.get("complete")))
    seeds = property(lambda self: int(self.table.get("seeds") or 0))
    runs = property(lambda self: list(self.table.get("runs", [])))
    cells = property(lambda self: list(self.table.get("cells", [])))

    @property
    def varied(self) -> list[str]:
        """The varied keys ("section.key", or "section" for a whole table), in --vary order."""
        first = (self.table.get("runs") or [{}])[0]
        return [k for k in first if k not in _RUN_ENTRY_KEYS]

    def run(self, entry: dict) -> Run:
        """The run directory of one entry of `runs`."""
        return load_run(self.path / entry["run"])

    def load_runs(self) -> list[Run]:
        """Every run of the sweep as a Run, in plan order."""
        return [self.run(entry) for entry in self.runs]

    @property
    def metric_window(self) -> tuple[float, float] | None:
        """The metric window of the sweep's runs (from the first run whose summary gives it)."""
        for entry in self.runs:
            if entry.get("finished"):
                window = self.run(entry).metric_window
                if window is not None:
                    return window
        return None

    def frame(self, runs: bool = False):
        """The cell table (or with runs=True the run table) as a pandas DataFrame: the varied
        keys, then metric columns (`<metric>_mean`, `_std`, `_ci95_low`, `_ci95_high` per cell;
        `<metric>` per run)."""
        import pandas as pd

        entries = self.runs if runs or not self.cells else self.cells
        return pd.DataFrame([_frame_row(entry) for entry in entries])

    def plot(self, metric: str = "sigma_f_mean", x: str | None = None, ax=None, **kwargs):
        """The sweep plot (mjfanalysis.sweep_plot.plot_sweep): `metric` against the varied key
        `x`, mean and 95 % CI per cell, one line per value of the other varied keys. Returns the
        axes."""
        from .sweep_plot import plot_sweep

        return plot_sweep(self, metric, x=x, ax=ax, **kwargs)


def _frame_row(entry: dict) -> dict:
    row = {k: axis_value(v) for k, v in entry.items() if not k.startswith("metrics")}
    for name, m in (entry.get("metrics") or {}).items():
        if isinstance(m, dict) and "mean" in m:
            row[f"{name}_mean"], row[f"{name}_std"] = m["mean"], m["std"]
            row[f"{name}_ci95_low"], row[f"{name}_ci95_high"] = m["ci95"]
        elif isinstance(m, (int, float)) or m is None:
            row[name] = m
    return row


def load_sweep(path) -> Sweep:
    """A sweep directory (it holds sweep.json). Raises OSError / ValueError when unreadable."""
    path = Path(path)
    with open(path / "sweep.json") as f:
        return Sweep(path, json.load(f))


def window_label(window: tuple[float, float] | None) -> str:
    """"[25, 40] s" for a metric window; "the metric window" when unknown."""
    if window is None:
        return "the metric window"
    return f"[{window[0]:g}, {window[1]:g}] s"


def vehicle_name(v: int) -> str:
    return "leader" if v == 0 else f"follower {v}"


def short_event(e: dict) -> str:
    """'F6 flip 34.19 s': the label of an event mark (as the snapshots write it)."""
    who = "-".join("L" if v == 0 else f"F{v}" for v in e.get("vehicles") or [])
    return f"{who} {e.get('kind', '?')} {float(e.get('time_s', float('nan'))):.2f} s"


def describe_event(e: dict) -> str:
    """'follower 6 flipped at 34.19 s (tilt 95.2 deg)': the runner's own words (summary.json
    'what'), else composed from kind, vehicles and time."""
    if e.get("what"):
        return str(e["what"])
    who = " and ".join(vehicle_name(v) for v in e.get("vehicles") or [])
    return f"{who}: {e.get('kind', '?')} at {float(e.get('time_s', float('nan'))):.2f} s"


# Kinds marked in figures and snapshots: all but near misses (many, and no damage).
MARKED_EVENT_KINDS = ("flip", "ground_impact", "collision", "left_region")

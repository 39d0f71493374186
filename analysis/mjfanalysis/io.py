# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Reading a run directory: timeseries.csv, summary.json, config.toml (docs/ARCHITECTURE.md)."""

from __future__ import annotations

import csv
import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

NAN = float("nan")

try:  # the runner's own loader, when the Python module is built or installed
    from mjformation._core import read_csv as _module_reader
except ImportError:
    _module_reader = None


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
    if _module_reader is not None:
        header, data = _module_reader(str(path))  # columns x rows
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


@dataclass
class Run:
    """One run directory. `status` is "complete", "incomplete" (summary says complete = false)
    or "unfinished" (no summary.json: still running or killed)."""

    path: Path
    summary: dict | None = None
    config: dict | None = None
    config_error: str | None = None
    _ts: dict | None = field(default=None, repr=False)
    ts_error: str | None = None

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


@dataclass
class Sweep:
    """One sweep directory (mjformation sweep): sweep.json's runs and cells as written, plus
    each run as a Run. `runs[i]["run"]` names the run directory, `cells[j]["metrics"][key]`
    holds n, mean, ci95 over the seeds of that cell."""

    path: Path
    complete: bool
    seeds: int
    runs: list[dict]
    cells: list[dict]

    def run(self, entry: dict) -> Run:
        """The run directory of one entry of `runs`."""
        return load_run(self.path / entry["run"])

    @property
    def metric_window(self) -> tuple[float, float] | None:
        """The metric window of the sweep's runs (from the first run whose summary gives it)."""
        for entry in self.runs:
            if entry.get("finished"):
                window = self.run(entry).metric_window
                if window is not None:
                    return window
        return None


def load_sweep(path) -> Sweep:
    """A sweep directory (it holds sweep.json). Raises OSError / ValueError when unreadable."""
    path = Path(path)
    with open(path / "sweep.json") as f:
        data = json.load(f)
    return Sweep(path=path, complete=bool(data.get("complete")), seeds=int(data.get("seeds", 0)),
                 runs=list(data.get("runs", [])), cells=list(data.get("cells", [])))


def window_label(window: tuple[float, float] | None) -> str:
    """"[25, 40] s" for a metric window; "the metric window" when unknown."""
    if window is None:
        return "the metric window"
    return f"[{window[0]:g}, {window[1]:g}] s"

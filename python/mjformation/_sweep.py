# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjformation.sweep: the CLI's `sweep` in-process (same plan, threads, tables and bytes)."""

from __future__ import annotations

import json
import signal
import tempfile
from pathlib import Path

from . import _core


class Sweep:
    """A sweep directory: cells (sweep.json; per cell mean/std/95 % CI with seeds), runs."""

    def __init__(self, path):
        self.path = Path(path)
        self.table = json.loads((self.path / "sweep.json").read_text())

    @property
    def complete(self) -> bool:
        return bool(self.table.get("complete"))

    @property
    def cells(self) -> list[dict]:
        """One dict per grid cell (with seeds) or per run (without)."""
        return self.table.get("cells", self.table["runs"])

    @property
    def runs(self):
        from . import Run

        return [Run(self.path / r["run"]) for r in self.table["runs"]]

    def frame(self, runs: bool = False):
        """The cell table as a pandas DataFrame: the varied keys, then metric columns
        (`<metric>_mean`, `_std`, `_ci95_low`, `_ci95_high` with seeds; `<metric>` without)."""
        import pandas as pd

        rows = []
        for entry in self.table["runs"] if runs or "cells" not in self.table else self.cells:
            row = {k: _scalar(v) for k, v in entry.items() if k != "metrics"}
            for name, m in (entry.get("metrics") or {}).items():
                if isinstance(m, dict) and "mean" in m:
                    row[f"{name}_mean"], row[f"{name}_std"] = m["mean"], m["std"]
                    row[f"{name}_ci95_low"], row[f"{name}_ci95_high"] = m["ci95"]
                elif isinstance(m, (int, float)) or m is None:
                    row[name] = m
            rows.append(row)
        return pd.DataFrame(rows)


    def plot(self, metric: str = "sigma_f_mean", x: str | None = None, ax=None, label=None):
        """metric against the varied parameter `x` (default: the first one), per cell the mean
        with its 95 % Student-t interval (needs seeds), and each run as a dot. Returns the axes."""
        import matplotlib.pyplot as plt

        cells, runs = self.frame(), self.frame(runs=True)
        if f"{metric}_mean" not in cells:
            raise ValueError(f"no per-cell statistics of '{metric}' (a sweep with seeds= has them)")
        keys = [k for k in cells.columns if "." in k]
        x = x or (keys[0] if keys else None)
        if x is None:
            raise ValueError("the sweep varies no parameter: nothing to plot against")
        ax = ax or plt.subplots(figsize=(6, 3.5))[1]
        mean = cells[f"{metric}_mean"]
        err = [mean - cells[f"{metric}_ci95_low"], cells[f"{metric}_ci95_high"] - mean]
        ax.errorbar(cells[x], mean, yerr=err, fmt="o-", capsize=4,
                    label=label or f"mean of {self.table['seeds']} seeds, 95 % CI")
        ax.plot(runs[x], runs[metric], "k.", alpha=0.4, label="runs")
        ax.set(xlabel=x, ylabel=metric)
        ax.legend()
        return ax


def _scalar(v):
    if isinstance(v, str):
        try:
            return json.loads(v)
        except ValueError:
            return v
    return v


def sweep(experiment, vary=None, seeds=None, jobs=2, set=None, out=None, render=False,
          overwrite=False, resume=False, formation=None, plugin_path=None) -> Sweep:
    """Runs the grid `vary` = {"section.key": [v1, v2, ...]} x `seeds` runs per cell, `jobs`
    at a time (the GIL released), and returns the Sweep (cells with 95 % CI, runs).

    out=None: a temporary folder. Ctrl-C keeps the finished runs and raises KeyboardInterrupt
    (finish with resume=True). The CLI's exit code 3 (some run failed) is not an exception:
    see Sweep.complete and each cell's complete_runs.
    """
    from . import _LawInUse, _overrides, _plugin_path, _toml_value

    out = Path(tempfile.mkdtemp(prefix="mjformation_sweep_")) / "sweep" if out is None else Path(out)
    args = ["sweep", str(experiment), "--out", str(out), "--jobs", str(int(jobs))]
    for key, values in (vary or {}).items():
        args += ["--vary", f"{key}=" + ",".join(_toml_value(v) for v in values)]
    if seeds:
        args += ["--seeds", str(int(seeds))]
    for p in _plugin_path(plugin_path):
        args += ["--plugin-path", p]
    if not render:
        args.append("--no-render")
    if overwrite:
        args.append("--overwrite")
    if resume:
        args.append("--resume")
    with _LawInUse(formation, experiment) as law_overrides:
        # Bad input raises ValueError with the runner's FILE:LINE: [section] key message.
        _core.check(str(experiment), law_overrides + _overrides(set), _plugin_path(plugin_path))
        for o in law_overrides + _overrides(set):
            args += ["--set", o]
        code = _core.command_line(args)
    if code == 128 + signal.SIGINT:
        raise KeyboardInterrupt(f"mjformation.sweep interrupted; finished runs kept in {out}")
    if code in (1, 2) or not (out / "sweep.json").is_file():
        raise ValueError(f"mjformation sweep {' '.join(args[1:])}: exit {code} (see stderr)")
    return Sweep(out)

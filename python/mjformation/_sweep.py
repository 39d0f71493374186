# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjformation.sweep: the CLI's `sweep` in-process (same plan, threads, tables and bytes)."""

from __future__ import annotations

import signal
import tempfile
from pathlib import Path

from mjfanalysis.io import Sweep, load_sweep

from . import _core


def sweep(experiment, vary=None, seeds=None, jobs=2, set=None, out=None, render=False,
          overwrite=False, resume=False, formation=None, plugin_path=None) -> Sweep:
    """Runs the grid `vary` = {"section.key": [v1, v2, ...]} x `seeds` runs per cell, `jobs`
    at a time (the GIL released), and returns the Sweep (mjfanalysis.io.Sweep: cells with 95 %
    CI, runs).

    render=False (the default) renders nothing and skips [render]'s checks; a shorter
    run.duration alone scales the file's metric_window with it (stated in a UserWarning), as
    mjformation.run. out=None: a temporary folder. Ctrl-C keeps the finished runs and raises KeyboardInterrupt
    (finish with resume=True). The CLI's exit code 3 (some run failed) is not an exception:
    see Sweep.complete and each cell's complete_runs.
    """
    from . import (_experiment_file, _LawInUse, _overrides, _plugin_path, _proportionate_window,
                   _toml_value)

    experiment = _experiment_file(experiment)

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
    overrides = _overrides(set)
    overrides += _proportionate_window(experiment, overrides, "mjformation.sweep")
    with _LawInUse(formation, experiment) as law_overrides:
        # Bad input raises ValueError with the runner's FILE:LINE: [section] key message; without
        # rendering, [render]'s checks are skipped as the runs skip them (--no-render).
        _core.check(str(experiment), law_overrides + overrides, _plugin_path(plugin_path),
                    bool(render))
        for o in law_overrides + overrides:
            args += ["--set", o]
        code = _core.command_line(args)
    if code == 128 + signal.SIGINT:
        raise KeyboardInterrupt(f"mjformation.sweep interrupted; finished runs kept in {out}")
    if code in (1, 2) or not (out / "sweep.json").is_file():
        raise ValueError(f"mjformation sweep {' '.join(args[1:])}: exit {code} (see stderr)")
    return load_sweep(out)

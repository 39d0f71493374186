# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""analysis/network_study.py on small hand-made sweep.json files."""
import importlib.util
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("network_study", ROOT / "analysis/network_study.py")
study = importlib.util.module_from_spec(spec)
spec.loader.exec_module(study)

JACOBI3 = '{mode="per_agent",coupling="jacobi",jacobi_rounds=3}'
LAST = '{mode="per_agent",coupling="last_input"}'
SOLVE = '{mode="per_agent",coupling="central_solve"}'


def test_coupling_labels():
    assert study.coupling_label(LAST) == "last_input"
    assert study.coupling_label(JACOBI3) == "jacobi_m3"
    assert study.coupling_label('{mode="per_agent",coupling="jacobi"}') == "jacobi_m1"
    assert study.coupling_label('{mode="per_agent",coupling="central_solve"}') == "central_solve"


def metric(n, mean, low, high):
    return {"n": n, "mean": mean, "std": 0.1, "ci95": [low, high]}


def write_sweep(folder, cells, runs, complete=True):
    folder.mkdir(parents=True)
    (folder / "sweep.json").write_text(
        json.dumps({"complete": complete, "seeds": 3, "runs": runs, "cells": cells}))


def test_tables_say_diverged_reached_and_not_run(tmp_path):
    base = tmp_path / "pointmass" / "exp2"
    write_sweep(base / "central", [{"seeds": 3, "complete_runs": 3, "metrics": {
        "sigma_f_mean": metric(3, 0.084, 0.08, 0.088),
        "reaching_time_s": metric(3, 1.4, 1.3, 1.5)}}],
        [{"run": f"seed={k}", "finished": True, "complete": True} for k in range(3)])
    cells, runs = [], []
    for execution, complete, reached in ((JACOBI3, 3, 2), (LAST, 0, 0), (SOLVE, 3, 0)):
        m = {}
        if complete:
            sigma = 0.1 if execution == SOLVE else 0.2
            m["sigma_f_mean"] = metric(complete, sigma, sigma - 0.1, sigma + 0.1)
        if reached:
            m["reaching_time_s"] = metric(reached, 4.0, 3.0, 5.0)
        cells.append({"execution": execution, "network.latency": "0.01", "network.loss": "0.2",
                      "seeds": 3, "complete_runs": complete, "metrics": m})
        for k in range(3):
            finished = not (execution == LAST and k == 2)  # one run of last_input not run
            runs.append({"execution": execution, "network.latency": "0.01",
                         "network.loss": "0.2", "run": f"r{k}", "finished": finished,
                         "complete": finished and k < complete})
    write_sweep(base / "per_agent", cells, runs, complete=False)
    table = tmp_path / "table.md"
    out = subprocess.run([sys.executable, str(ROOT / "analysis/network_study.py"), str(tmp_path),
                          "--table", str(table), "--figure", str(tmp_path / "fig.png")],
                         capture_output=True, text=True, check=True).stdout
    assert "| central mode | - | 0.084 ± 0.004; t_r 1.4 ± 0.1 s |" in out
    assert "| jacobi_m3 | 10 ms | 0.2 ± 0.1; t_r 4 ± 1 s (2/3 reached) |" in out
    assert "| last_input | 10 ms | diverged (2/2) (1 not run) |" in out
    assert "(SWEEP INCOMPLETE)" in out
    # 0.2 m against central 0.084 m is more than twice: jacobi_m3 does not hold; last_input
    # diverged.
    assert "| exp2 | pointmass | 0.084 | jacobi_m3 | fails at 0 ms |" in out
    assert "| exp2 | pointmass | 0.084 | last_input | fails at 0 ms |" in out
    assert "| exp2 | pointmass | 0.084 | central_solve | holds to 10 ms (all) |" in out
    assert "| central_solve | 10 ms | 0.1 ± 0.1; not reached |" in out
    assert table.read_text().count("### exp2, pointmass") == 1
    assert (tmp_path / "fig.png").stat().st_size > 1000

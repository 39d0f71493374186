# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""analysis/timing_study.py on small hand-made sweep.json files."""
import importlib.util
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("timing_study", ROOT / "analysis/timing_study.py")
study = importlib.util.module_from_spec(spec)
sys.path.insert(0, str(ROOT / "analysis"))
spec.loader.exec_module(study)

SYNC_JACOBI = ('{mode="per_agent",coupling="jacobi",jacobi_rounds=3,predict="input",'
               'clock_offset=0.025,clock_sync=true}')
SOLVE = '{mode="per_agent",coupling="central_solve",predict="input"}'


def test_labels_read_coupling_and_prediction():
    assert study.label(SYNC_JACOBI) == ("jacobi_m3", "input")
    assert study.label(SOLVE) == ("central_solve", "input")


def test_largest_holding_stops_at_the_first_latency_that_fails():
    ref = 0.1
    by_lat = {0.0: (0.1, 0.0), 0.01: (0.14, 0.0), 0.02: (0.16, 0.0), 0.03: (0.1, 0.0)}
    assert study.largest_holding(by_lat, [0.0, 0.01, 0.02, 0.03], ref) == 0.01
    assert study.largest_holding({0.0: None}, [0.0], ref) is None  # diverged at 0


def write_sweep(folder, cells):
    folder.mkdir(parents=True)
    (folder / "sweep.json").write_text(
        json.dumps({"complete": True, "seeds": 3, "runs": [], "cells": cells}))


def cell(mean, complete=3, **keys):
    return {"seeds": 3, "complete_runs": complete, **keys,
            "metrics": {"sigma_f_mean": {"n": complete, "mean": mean, "std": 0.01,
                                         "ci95": [mean - 0.01, mean + 0.01]}}}


def test_the_synchronised_part_is_tabled_at_its_broadcast_rate(tmp_path):
    base = tmp_path / "pointmass" / "exp2"
    write_sweep(base / "central", [cell(0.1)])
    write_sweep(base / "off_phase_sync", [
        cell(0.12, execution=SYNC_JACOBI, **{"network.latency": "0"}),
        cell(0.2, execution=SYNC_JACOBI, **{"network.latency": "0.01"}),
        cell(0.3, complete=1, execution=SYNC_JACOBI, **{"network.latency": "0.02"})])
    table = tmp_path / "table.md"
    out = subprocess.run([sys.executable, str(ROOT / "analysis/timing_study.py"), str(tmp_path),
                          "--table", str(table)], capture_output=True, text=True, check=True,
                         env={"PYTHONPATH": str(ROOT / "analysis")}).stdout
    assert "### off_phase_sync:" in out
    # 50 Hz (the part's broadcast), holds at 0 ms (1.2x), not at 10 ms (2x), 20 ms diverged.
    assert ("| jacobi_m3 | input | 0 % | 50 Hz | 0 ms | n/a | 0.12 ± 0.01 | 0.2 ± 0.01 | "
            "diverged |") in out
    assert table.read_text() + "\n" == out  # print adds the newline

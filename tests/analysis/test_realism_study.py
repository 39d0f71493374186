# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""analysis/realism_study.py on a small hand-made sweep.json."""
import importlib.util
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("realism_study", ROOT / "analysis/realism_study.py")
study = importlib.util.module_from_spec(spec)
spec.loader.exec_module(study)


def test_labels():
    assert study.noise_label('{preset="ideal"}') == "ideal"
    assert study.noise_label('{preset="typical"}') == "typical"
    assert study.noise_label('{preset="typical",scale=3.0}') == "3x typical"
    assert study.wind_speed('{turbulence="moderate"}') == 0.0
    assert study.wind_speed('{mean=[6.0,0.0,0.0],turbulence="moderate"}') == 6.0


def test_table_marks_not_run_and_stopped_runs(tmp_path):
    cells, runs = [], []
    for noise in ['{preset="ideal"}', '{preset="typical"}']:
        complete = 2 if noise.endswith('"ideal"}') else 1
        cells.append({"sensors": noise, "wind": '{turbulence="moderate"}', "seeds": 3,
                      "complete_runs": complete,
                      "metrics": {"sigma_f_mean": {"n": complete, "mean": 2.0,
                                                   "std": 0.5, "ci95": [1.0, 3.0]}}})
        for k in range(3):
            finished = k < 2
            runs.append({"sensors": noise, "wind": '{turbulence="moderate"}', "run": f"r{k}",
                         "finished": finished, "complete": finished and k < complete})
    folder = tmp_path / "exp2"
    folder.mkdir()
    (folder / "sweep.json").write_text(json.dumps(
        {"complete": False, "seeds": 3, "runs": runs, "cells": cells}))
    out = subprocess.run([sys.executable, str(ROOT / "analysis/realism_study.py"), str(tmp_path)],
                         capture_output=True, text=True, check=True).stdout
    assert "SWEEP INCOMPLETE" in out
    assert "| ideal | 2 [1, 3] (1 not run) |" in out
    assert "| typical | 2 [1, 3] (1 of 2 stopped early) (1 not run) |" in out
    assert "| 3x typical | - |" in out

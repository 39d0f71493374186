# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""analysis/mjfanalysis/robustness.py on a hand-made sweep folder with known answers."""

import json
import math

import numpy as np

from mjfanalysis import robustness


def _run(folder, name, final_error, roll_peak_deg):
    run = folder / name
    run.mkdir(parents=True)
    metrics = {"sigma_f_mean": 1.5, "max_final_slot_error_m": final_error,
               "rms_tilt_deg_in_window": [10.0, 20.0], "tilt_oscillation_hz_in_window": [1.2, 1.4],
               "max_follower_tilt_deg_in_window": 25.0}
    (run / "summary.json").write_text(json.dumps({"metrics": metrics}))
    t = np.linspace(0, 1, 11)
    roll = np.radians(roll_peak_deg) * np.sin(np.pi * t)
    cols = ["t", "uav0_roll", "uav0_pitch", "uav1_roll", "uav1_pitch", "uav2_roll", "uav2_pitch"]
    rows = [[ti, 3.0, 0.0, r, 0.0, 0.5 * r, 0.0] for ti, r in zip(t, roll)]
    (run / "timeseries.csv").write_text(
        ",".join(cols) + "\n" + "\n".join(",".join(f"{v:.9g}" for v in row) for row in rows))


def test_map_reads_sweeps_and_flags_reach_refusal_and_limit(tmp_path):
    folder = tmp_path / "exp2__geometric"
    folder.mkdir()
    _run(folder, "tilt_max=0.55", 0.05, 30.0)   # reached, 30 deg < 31.5 deg limit
    _run(folder, "tilt_max=0.35", 40.0, 35.0)   # not reached, 35 deg > 20 + 10 deg
    refused = "x.toml:3: [attitude] plugin 'p' refused its configuration: no"
    runs = [{"attitude.tilt_max": "0.55", "complete": True, "run": "tilt_max=0.55", "error": None},
            {"attitude.tilt_max": "0.35", "complete": True, "run": "tilt_max=0.35", "error": None},
            {"attitude.tilt_max": "0.78", "complete": False, "run": "tilt_max=0.78",
             "error": refused}]
    (folder / "sweep.json").write_text(json.dumps({"complete": False, "seeds": 0, "runs": runs}))
    cells = {c.tilt_max: c for c in robustness.read_map(tmp_path)}
    assert cells[0.55].reached and not cells[0.35].reached
    assert cells[0.78].refused and not cells[0.78].reached
    # The leader (uav0, tilted 3 rad) is not a follower: only uav1.. count.
    assert math.isclose(cells[0.55].max_tilt_deg_run, 30.0, abs_tol=1e-6)
    assert math.isclose(cells[0.35].over_limit_deg, 35.0 - math.degrees(0.35), abs_tol=1e-6)
    assert math.isclose(cells[0.55].rms_tilt_mean, 15.0)
    text = "\n".join(robustness.markdown(list(cells.values())))
    assert "**refused**" in text and "| yes |" in text and "**no**" in text
    assert "**+14.9**" in text  # beyond the limit by more than 10 deg is flagged
    compact = "\n".join(robustness.compact_markdown(list(cells.values())))
    assert "**yes** · 1.50 · 15.0 · 30.0" in compact and "refused" in compact
    assert "no · 1.50 · 15.0 · 35.0 (**+15 over**)" in compact
    robustness.write_csv(list(cells.values()), tmp_path / "map.csv")
    assert (tmp_path / "map.csv").read_text().count("\n") == 4


def test_report_shows_follower_motion_and_the_map(tmp_path):
    from conftest import make_run
    from mjfanalysis.report import write_report
    path, _, _ = make_run(tmp_path, "exp2", exp=2)
    summary = json.loads((path / "summary.json").read_text())
    summary["metrics"].update({"rms_tilt_deg_in_window": [10.0, 14.0],
                               "tilt_oscillation_hz_in_window": [1.2, 1.4],
                               "rms_thrust_variation_n_in_window": [0.5, 0.7]})
    (path / "summary.json").write_text(json.dumps(summary))
    (tmp_path / "robustness").mkdir()
    (tmp_path / "robustness" / "map.md").write_text("| a map |\n")
    text = write_report(tmp_path, tmp_path / "report").read_text()
    assert "## Follower motion in the metric window" in text
    assert "| 12.0 [10.0, 14.0] | 1.30 | 0.6 [0.5, 0.7] |" in text
    assert "## Robustness map" in text and "| a map |" in text

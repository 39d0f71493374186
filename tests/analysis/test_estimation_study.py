# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""analysis/estimation_study.py: the study's table from sweep.json files as `sweep` writes them."""
import importlib.util
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("estimation_study", ROOT / "analysis/estimation_study.py")
study = importlib.util.module_from_spec(spec)
spec.loader.exec_module(study)


def _cell(sensors, mean, ci, events=0, free=None):
    cell = {"sensors": sensors, "seeds": 3, "complete_runs": 3, "runs_with_safety_events": events,
            "metrics": {"sigma_f_mean": {"n": 3, "mean": mean, "std": 0.1, "ci95": ci}}}
    if free is not None:
        cell["metrics_event_free"] = {"sigma_f_mean": {"n": 2, "mean": free, "std": 0.1,
                                                       "ci95": [free - 0.1, free + 0.1]}}
    return cell


def test_table_has_a_row_per_cell_with_intervals_and_event_free_statistics(tmp_path):
    sweep = tmp_path / "exp2" / "quadrotor"
    sweep.mkdir(parents=True)
    table = {"complete": True, "seeds": 3,
             "runs": [{"sensors": '{preset="rtk"}', "seed": 1, "complete": True, "finished": True,
                       "run": "x", "error": None, "safety_events": 0, "metrics": {}}],
             "cells": [_cell('{preset="rtk"}', 1.3, [1.27, 1.32]),
                       _cell('{preset="consumer_gnss"}', 4.15, [2.18, 6.12], events=1, free=3.17)]}
    (sweep / "sweep.json").write_text(json.dumps(table))
    text = study.table(tmp_path)
    assert "### exp2/quadrotor (3 seeds per cell)" in text
    assert "| {preset=\"rtk\"} | 3/3 | 0 | 1.3 [1.27, 1.32] | = |" in text
    assert "| {preset=\"consumer_gnss\"} | 3/3 | 1 | 4.15 [2.18, 6.12] | 3.17 [3.07, 3.27] |" in text


def test_an_empty_folder_is_refused(tmp_path):
    assert study.main([str(tmp_path)]) == 1

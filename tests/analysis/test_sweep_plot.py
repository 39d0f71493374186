# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjfanalysis.sweep_plot and analysis/sweep_plot.py on a hand-made sweep.json with known answers
(the real sweep: tests/python/test_sweep_plot.py)."""
import json
import subprocess
import sys
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

from mjfanalysis import load_sweep  # noqa: E402
from mjfanalysis.io import axis_value  # noqa: E402
from mjfanalysis.sweep_plot import plot_sweep, sweep_lines  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def stats(n, mean, low, high, std=0.1):
    return {"n": n, "mean": mean, "std": std, "ci95": [low, high]}


def write_sweep(folder, quoted):
    """q in {1, 2} x sensors in {none, typical} x 3 seeds. Cell (q=2, none): one of its three
    runs had a safety event; cell (q=1, typical): every run gave the same value (std 0)."""
    none = '"none"' if quoted else "none"
    cells, runs = [], []
    for sensors in (none, "typical"):
        for q in ("1.0", "2.0"):
            events = 1 if (q, sensors) == ("2.0", none) else 0
            constant = (q, sensors) == ("1.0", "typical")
            base = float(q) + (0.5 if sensors == "typical" else 0.0)
            cell = {"formation.q": q, "sensors": sensors, "seeds": 3, "complete_runs": 3,
                    "runs_with_safety_events": events, "event_free_complete_runs": 3 - events,
                    "metrics": {"sigma_f_mean": stats(3, base + 0.3, base, base + 0.6)}}
            cell["metrics_event_free"] = {"sigma_f_mean": stats(3 - events, base, base - 0.2,
                                                                base + 0.2)}
            if constant:  # no event here: both tables hold the same runs
                cell["metrics"]["sigma_f_mean"] = stats(3, base, base, base, std=0.0)
                cell["metrics_event_free"] = cell["metrics"]
            cells.append(cell)
            for seed in range(3):
                value = base if constant else base + 0.1 * (seed - 1) + (1.0 if seed < events else 0)
                runs.append({"formation.q": q, "sensors": sensors, "seed": seed, "complete": True,
                             "finished": True, "run": f"r_{q}_{sensors}_{seed}", "error": None,
                             "safety_events": int(seed < events),
                             "metrics": {"sigma_f_mean": value}})
    folder.mkdir(parents=True)
    (folder / "sweep.json").write_text(json.dumps({"complete": True, "seeds": 3, "runs": runs,
                                                   "cells": cells}))
    return folder


@pytest.mark.parametrize("quoted", [True, False])
def test_lines_per_other_value_events_left_out_and_constants(tmp_path, quoted):
    sweep = load_sweep(write_sweep(tmp_path / "s", quoted))
    assert sweep.varied == ["formation.q", "sensors"]
    x, lines = sweep_lines(sweep, "sigma_f_mean")
    assert x == "formation.q"
    assert [line.label for line in lines] == ["sensors=none", "sensors=typical"]  # both quotings
    none, typical = lines
    assert [p.x for p in none.points] == [1.0, 2.0]
    # The event-free statistics, and the run with the event counted, not drawn
    assert none.points[1].n == 2 and none.points[1].left_out == 1 and none.left_out == 1
    assert none.points[1].mean == 2.0 and len(none.points[1].runs) == 2
    assert typical.left_out == 0 and not typical.points[0].has_interval  # constant here
    # Over all complete runs instead: the run with the event is back, the constant stays one
    _, every = sweep_lines(sweep, "sigma_f_mean", valid_only=False)
    assert every[0].points[1].n == 3 and every[0].points[1].mean == pytest.approx(2.3)
    assert every[0].left_out == 0 and not every[1].points[0].has_interval
    # Against the other key: categorical x, one line per q
    x, by_sensors = sweep_lines(sweep, "sigma_f_mean", x="sensors")
    assert [line.label for line in by_sensors] == ["formation.q=1", "formation.q=2"]
    assert [p.x for p in by_sensors[0].points] == ["none", "typical"]


def test_plot_draws_intervals_only_where_there_are_some(tmp_path):
    sweep = load_sweep(write_sweep(tmp_path / "s", quoted=True))
    ax = plot_sweep(sweep, "sigma_f_mean")
    assert len(ax.containers) == 3  # four cells, one constant: three error bars
    # A sweep.json from before the rule (no left_out_events): any event left its run out, and
    # the caption says so
    assert "1 left out: any safety event" in ax.get_title()
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[:2] == ["sensors=none (1 run(s) left out)", "sensors=typical"]
    assert "no interval (constant or one run)" in labels


def test_bad_requests_are_clear_errors(tmp_path):
    sweep = load_sweep(write_sweep(tmp_path / "s", quoted=True))
    with pytest.raises(ValueError, match="no metric 'nope'"):
        sweep_lines(sweep, "nope")
    with pytest.raises(ValueError, match="'run.seed' is not varied"):
        sweep_lines(sweep, "sigma_f_mean", x="run.seed")
    out = subprocess.run([sys.executable, str(ROOT / "analysis/sweep_plot.py"), str(tmp_path),
                          "--metric", "sigma_f_mean"], capture_output=True, text=True)
    assert out.returncode == 2 and "sweep.json" in out.stderr


def test_axis_values_decode_both_quotings():
    assert axis_value('"none"') == "none" and axis_value("none") == "none"
    assert axis_value("0.05") == 0.05 and axis_value('{preset = "typical"}') == '{preset = "typical"}'


def test_near_misses_are_kept_and_flips_left_out_with_the_reason(tmp_path):
    """The runner's sweep.json since invalidating events: q=1 has three runs, each with a near
    miss (reported only, kept); q=2 has one flip among three (left out). The q=1 cell is not
    emptied, and the caption and table say how many runs were left out and why."""
    cells, runs = [], []
    for q, kinds in (("1.0", ["near_miss"] * 3), ("2.0", ["", "flip", ""])):
        values = [float(q) + 0.1 * k for k in range(3)]
        valid = [v for v, kind in zip(values, kinds) if kind != "flip"]
        mean = sum(valid) / len(valid)
        cells.append({"formation.q": q, "seeds": 3, "complete_runs": 3,
                      "runs_with_safety_events": sum(1 for k in kinds if k), "runs_left_out":
                      kinds.count("flip"), "valid_complete_runs": len(valid),
                      "metrics": {"sigma_f_mean": stats(3, sum(values) / 3, 0, 9)},
                      "metrics_valid": {"sigma_f_mean": stats(len(valid), mean, mean - 0.1,
                                                              mean + 0.1)}})
        for seed, (v, kind) in enumerate(zip(values, kinds)):
            entry = {"formation.q": q, "seed": seed, "complete": True, "finished": True,
                     "run": f"r{q}_{seed}", "error": None, "safety_events": int(bool(kind)),
                     "metrics": {"sigma_f_mean": v}}
            if kind:
                entry["first_safety_event"] = kind
                entry["invalidating_events"] = int(kind == "flip")
            runs.append(entry)
    folder = tmp_path / "s"
    folder.mkdir()
    (folder / "sweep.json").write_text(json.dumps({
        "complete": True, "seeds": 3, "runs": runs, "cells": cells,
        "left_out_events": ["flip", "ground_impact", "collision"]}))
    sweep = load_sweep(folder)
    assert sweep.varied == ["formation.q"]
    _, (line,) = sweep_lines(sweep, "sigma_f_mean")
    near, flip = line.points
    assert near.n == 3 and near.left_out == 0 and len(near.runs) == 3
    assert flip.n == 2 and flip.left_out == 1 and flip.mean == pytest.approx(2.1)
    ax = plot_sweep(sweep, "sigma_f_mean")
    assert "valid runs (1 left out: a flip, ground impact or collision)" in ax.get_title()
    out = subprocess.run([sys.executable, str(ROOT / "analysis/sweep_plot.py"), str(folder),
                          "--out", str(tmp_path / "p.png")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "1 complete run(s) left out: a flip, ground impact or collision." in out.stdout

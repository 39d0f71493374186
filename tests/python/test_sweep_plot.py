# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The sweep plot (analysis/sweep_plot.py, mjfanalysis.sweep_plot) on a small real sweep: Exp 2 on
the point mass for 2 s, q in {1.5, 4.5} x 3 seeds, starts jittered by 1.5 m: seed 1 starts two
followers overlapping (collision and near-miss events), seeds 2 and 3 fly event-free (their
closest gap, about 0.2 m, stays above the 0.05 m near-miss margin set here)."""

import os
import subprocess
import sys

import matplotlib
import pytest

matplotlib.use("Agg")

from mjfanalysis import load_sweep  # noqa: E402
from mjfanalysis.sweep_plot import plot_sweep, sweep_lines  # noqa: E402

SETTINGS = ['vehicles.model="pointmass"', 'attitude={plugin="pointmass_direct"}',
            "run.duration=2.0", "run.metric_window=[0.0, 2.0]", "render.snapshots=[]",
            "vehicles.start_jitter=1.5", "safety.near_miss_m=0.05"]


@pytest.fixture(scope="module")
def sweep_dir(cli, exp2, tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep_plot") / "sweep"
    args = [cli, "sweep", str(exp2), "--vary", "formation.q=1.5,4.5", "--seeds", "3", "--jobs",
            "2", "--no-render", "--out", str(out)]
    for s in SETTINGS:
        args += ["--set", s]
    assert subprocess.run(args, capture_output=True).returncode == 0
    return out


def test_the_sweep_has_safety_events_in_some_runs_only(sweep_dir):
    sweep = load_sweep(sweep_dir)
    assert [c["runs_with_safety_events"] for c in sweep.cells] == [1, 1]
    assert all(c["valid_complete_runs"] == 2 for c in sweep.cells)
    assert "statistics_over" in (sweep_dir / "sweep.csv").read_text().splitlines()[0]


def test_lines_are_the_valid_cells_and_count_what_is_left_out(sweep_dir):
    sweep = load_sweep(sweep_dir)
    x, (line,) = sweep_lines(sweep, "sigma_f_mean")
    assert x == "formation.q" and line.label == "" and line.left_out == 2
    for point, cell in zip(line.points, sweep.cells):
        free = cell["metrics_valid"]["sigma_f_mean"]
        assert (point.n, point.mean, [point.low, point.high]) == (2, free["mean"], free["ci95"])
        assert point.left_out == 1 and len(point.runs) == 2 and len(point.left_out_runs) == 1
        assert point.has_interval
    _, (every,) = sweep_lines(sweep, "sigma_f_mean", valid_only=False)
    assert [p.n for p in every.points] == [3, 3] and every.left_out == 0
    assert [p.mean for p in every.points] == [c["metrics"]["sigma_f_mean"]["mean"]
                                              for c in sweep.cells]


def test_constants_are_not_intervals(sweep_dir):
    sweep = load_sweep(sweep_dir)
    # Every run counts the same samples in its window: a constant, drawn as a point
    _, (line,) = sweep_lines(sweep, "sigma_f_samples")
    assert all(p.n == 2 and p.low == p.high and not p.has_interval for p in line.points)
    assert not plot_sweep(sweep, "sigma_f_samples").containers
    assert len(plot_sweep(sweep, "sigma_f_mean").containers) == 2


def test_the_command_line_writes_the_figure_and_the_table(sweep_dir, source, tmp_path):
    png = tmp_path / "sigma_f.png"
    env = dict(os.environ, PYTHONPATH=str(source / "analysis"))  # without the module as well
    out = subprocess.run([sys.executable, str(source / "analysis/sweep_plot.py"), str(sweep_dir),
                          "--metric", "sigma_f_mean", "--out", str(png)], env=env,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = [r for r in out.stdout.splitlines() if r.startswith("| - |")]
    assert len(rows) == 2 and all(r.split("|")[3].strip() == "2" for r in rows)  # n
    assert all(r.split("|")[6].strip() == "1" for r in rows)  # left out
    assert "regenerate: /usr/bin/python3 analysis/sweep_plot.py" in out.stdout

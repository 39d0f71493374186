# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
import math

import numpy as np
import pytest
from conftest import analytic_sigma, make_run

from mjfanalysis import metrics as M
from mjfanalysis.io import find_runs, load_run, read_timeseries


def test_read_timeseries_empty_cells_and_truncated_row(tmp_path):
    p = tmp_path / "timeseries.csv"
    p.write_text("t,sigma_f,uav0_sx\n0.0,1.5,\n0.01,1.25,0.5\n0.02,1.0")  # killed mid-line
    ts = read_timeseries(p)
    assert list(ts) == ["t", "sigma_f", "uav0_sx"]
    assert ts["t"].tolist() == [0.0, 0.01]
    assert math.isnan(ts["uav0_sx"][0]) and ts["uav0_sx"][1] == 0.5


def test_sigma_f_recomputed_matches_analytic(fake_run):
    d, t, _ = fake_run
    run = load_run(d)
    ts = run.timeseries
    assert M.vehicle_ids(ts) == list(range(7))
    expected = analytic_sigma(t, 5.0, 4.0, 0.2)
    omega = M.circle_omega(run.summary, run.config)
    assert omega == pytest.approx(0.314)
    got = M.sigma_f_recomputed(ts, omega)
    np.testing.assert_allclose(got, expected, rtol=1e-6, atol=1e-6)
    # Without omega: numerical derivative of f_ip; close, not exact.
    np.testing.assert_allclose(M.sigma_f_recomputed(ts, None), expected, rtol=5e-3, atol=5e-3)


def test_window_mean_constant_deviation(tmp_path):
    # Constant offset c in y only: sigma_f = sqrt(6) c exactly, so is its window mean.
    d, t, _ = make_run(tmp_path, "exp1_printed", exp=1, a=0.0, c=0.25)
    run = load_run(d)
    s = M.sigma_f_recomputed(run.timeseries, 0.314)
    assert M.window_mean(t, s, (25.0, 40.0)) == pytest.approx(math.sqrt(6) * 0.25, rel=1e-7)
    # Closed window with the runner's tolerance: 20 Hz on [25, 40] s is 301 samples.
    assert M.window_mask(t, (25.0, 40.0)).sum() == 301


def test_window_mean_exponential_vs_integral(fake_run):
    d, t, _ = fake_run
    run = load_run(d)
    mean = M.window_mean(t, M.sigma_f_recomputed(run.timeseries, 0.314), (25.0, 40.0))
    fine = np.linspace(25.0, 40.0, 200001)
    integral_mean = np.trapz(analytic_sigma(fine, 5.0, 4.0, 0.2), fine) / 15.0
    assert mean == pytest.approx(integral_mean, rel=1e-3)
    assert mean == pytest.approx(run.metric("sigma_f_mean"), rel=1e-7)


def test_final_slot_errors_and_radius(fake_run):
    d, t, _ = fake_run
    ts = load_run(d).timeseries
    err = M.final_slot_errors(ts)
    assert err.shape == (6,)
    np.testing.assert_allclose(err, math.hypot(5.0 * math.exp(-40.0 / 4.0), 0.2), rtol=1e-6)
    assert M.slot_radius(ts) == pytest.approx(10.0, rel=1e-7)


def test_paper_experiment_mapping():
    assert M.paper_experiment({"paper_experiment": 2}, "whatever") == 2
    assert M.paper_experiment({"paper_experiment": 0}, "exp1_printed") is None
    assert M.paper_experiment({}, "exp3_pointmass") == 3
    assert M.paper_experiment(None, "exp1_switching") == 1
    assert M.paper_experiment({}, "consensus_baseline") is None
    assert M.paper_experiment({}, "exp12") is None


def test_protocol_description(fake_run):
    run = load_run(fake_run[0])
    text = M.protocol_description(run.summary, run.config)
    assert text.startswith("smc_discrete (") and "T = 0.05 s" in text and "q = 4.5" in text


def test_find_runs_statuses(tmp_path):
    make_run(tmp_path, "exp2", exp=2)
    make_run(tmp_path, "exp3", exp=3, complete=False, t_end=12.0)
    make_run(tmp_path, "exp1_printed", exp=1, summary=False)
    (tmp_path / "not_a_run").mkdir()
    runs = {r.name: r for r in find_runs(tmp_path)}
    assert set(runs) == {"exp2", "exp3", "exp1_printed"}
    assert runs["exp2"].status == "complete"
    assert runs["exp3"].status == "incomplete" and "non-finite" in runs["exp3"].error
    assert runs["exp1_printed"].status == "unfinished"

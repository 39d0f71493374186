# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""A new user's short runs from Python: one duration implies a proportionate metric window
(stated in a warning), a sweep that renders nothing does not check [render] snapshots, a plain
parameter sweep (no seeds) plots, and the snapshot refusal says how to fix it."""

import matplotlib
import pytest

import mjformation

matplotlib.use("Agg")

POINT_MASS = {"vehicles.model": "pointmass", "attitude": {"plugin": "pointmass_direct"}}


def test_one_duration_implies_a_proportionate_window(exp2, tmp_path):
    # exp2.toml averages over [25, 40] s of 40 s: a 4 s run averages over [2.5, 4] s.
    with pytest.warns(UserWarning, match=r"proportionate window \[2\.5, 4\] s; pass run\.metric_window"):
        run = mjformation.run(exp2, set={**POINT_MASS, "run.duration": 4.0}, out=tmp_path / "r")
    assert run.summary["complete"]
    assert tuple(run.metric_window) == (2.5, 4.0)


def test_a_window_given_or_fitting_is_kept_without_a_warning(exp2, tmp_path, recwarn):
    run = mjformation.run(exp2, set={**POINT_MASS, "run.duration": 3.0,
                                     "run.metric_window": [1.0, 3.0]}, out=tmp_path / "r")
    assert tuple(run.metric_window) == (1.0, 3.0)
    assert not [w for w in recwarn if "proportionate" in str(w.message)]


def test_the_snapshot_refusal_says_how_to_fix_it(exp2, tmp_path):
    with pytest.warns(UserWarning, match="proportionate"):
        with pytest.raises(ValueError, match=r"snapshots: times must lie in \[0, duration\]: 10 s is "
                                             r"outside \[0, 2\] s \(set render\.snapshots .*render=False"):
            mjformation.run(exp2, set={**POINT_MASS, "run.duration": 2.0}, render=True,
                            out=tmp_path / "r")


@pytest.fixture(scope="module")
def plain_sweep(exp2, tmp_path_factory):
    """q in {1.5, 4.5}, one run each, 2 s without rendering: exp2.toml's snapshots at 10, 20 and
    40 s lie outside, which only a rendering sweep must refuse."""
    with pytest.warns(UserWarning, match="proportionate"):
        return mjformation.sweep(exp2, vary={"formation.q": [1.5, 4.5]},
                                 set={**POINT_MASS, "run.duration": 2.0},
                                 out=tmp_path_factory.mktemp("plain") / "sweep")


def test_a_sweep_without_rendering_skips_the_snapshot_check(plain_sweep):
    assert plain_sweep.complete and len(plain_sweep.runs) == 2 and not plain_sweep.cells


def test_a_plain_parameter_sweep_plots_one_point_per_run(plain_sweep):
    ax = plain_sweep.plot()
    (line,) = ax.get_lines()[:1]
    assert list(line.get_xdata()) == [1.5, 4.5]
    assert list(line.get_ydata()) == [r["metrics"]["sigma_f_mean"] for r in plain_sweep.runs]
    assert "no seeds: no interval" in ax.get_title()

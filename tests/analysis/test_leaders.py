# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The non-cooperative leader section's own computations (analysis/mjfanalysis/leaders.py)."""

import math
from pathlib import Path

import numpy as np
import pytest

from mjfanalysis import leaders
from mjfanalysis.io import Run
from mjfanalysis.leaders import PeriodPoint


def _run(s1x, s1y, delta=0.1, discrete=True):
    t = np.arange(len(s1x)) * 0.01
    summary = {"complete": True, "plugin_report": {"delta": delta},
               "plugins": {"formation": {"name": "smc_discrete" if discrete else "smc_continuous"}}}
    config = {"formation": {"k": [3.0, 1.0], "eps": 0.05, "q": 4.5, "period": 0.05,
                            "u_min": -1.0, "u_max": 1.0},
              "topology": {"leader_links": [1]}}
    run = Run(path=Path("/nonexistent/run"), summary=summary, config=config)
    run._ts = {"t": t, "uav0_px": 0 * t, "uav1_px": 0 * t, "uav1_sx": np.asarray(s1x, float),
               "uav1_sy": np.asarray(s1y, float), "uav2_px": 0 * t,
               "uav2_sx": np.full(len(t), 0.005), "uav2_sy": 0 * t}
    return run


def test_band_tested_on_the_window_against_delta():
    n = 4100  # t = 0 .. 41 s at 100 Hz; window [25, 40] s
    sx = np.full(n, 5.0)
    sx[2400:] = 0.05
    sx[3000] = 0.25  # one excursion inside the window: counted
    sy = np.zeros(n)
    s = leaders.sliding_stats(_run(sx, sy))
    assert s.max_window == pytest.approx(0.25)
    assert s.ratio == pytest.approx(2.5)
    # Follower 2 has no leader link: Delta_2 = eps T = 0.0025, and |s_2| = 0.005 is twice it;
    # follower 1's own band is Delta2 = eps T + k2 T (u_max - u_min) = 0.1025.
    assert s.ratio_own == pytest.approx(max(0.25 / 0.1025, 2.0))
    assert math.isnan(s.reaching_time)  # no reaching_time_s in the summary


def test_continuous_has_no_ratio():
    n = 4100
    s = leaders.sliding_stats(_run(np.full(n, 0.002), np.zeros(n), delta=float("nan"),
                                   discrete=False))
    assert s.max_window == pytest.approx(0.005)  # follower 2's
    assert math.isnan(s.ratio) and math.isnan(s.ratio_own)


def test_mean_ci_student_t():
    m, h = leaders.mean_ci([1.0, 2.0, 3.0])
    assert m == pytest.approx(2.0)
    assert h == pytest.approx(4.303 * 1.0 / math.sqrt(3))
    assert math.isnan(leaders.mean_ci([5.0])[1])


def test_fitted_slope_recovers_a_power_law():
    pts = [PeriodPoint(T, [3.0 * T**0.8], 0, 0, 0) for T in (0.005, 0.01, 0.05, 0.1, 0.2)]
    slope, half = leaders.fitted_slope(pts)
    assert slope == pytest.approx(0.8, abs=1e-9)
    assert half == pytest.approx(0.0, abs=1e-6)


def test_theory_curves_parsed(tmp_path):
    text = ("[ info ] curve 1: bang_bang leader at +-r u_max\n[ info ]   T      r   max  bound\n"
            "[ info ]   0.01  1.00     1.000     1.000\n[ info ]   0.01  1.50     4.878     4.878\n"
            "[ info ] curve 2: declared\n[ info ]   0.20  0.50     1.429     1.476\n")
    p = tmp_path / "curves.txt"
    p.write_text(text)
    c = leaders.read_theory_curves(p)
    assert c[1] == [(0.01, 1.0, 1.0, 1.0), (0.01, 1.5, 4.878, 4.878)]
    assert c[2] == [(0.2, 0.5, 1.429, 1.476)]


def test_names_parsed():
    m = leaders.NAME_RE.match("exp1_exponential_bang_bang_s3_pointmass")
    assert m.groups() == ("exp1_exponential", "bang_bang", "3", "_pointmass")
    m = leaders.NAME_RE.match("consensus_baseline_lemniscate")
    assert m.groups() == ("consensus_baseline", "lemniscate", None, None)

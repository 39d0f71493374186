# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The benchmark's tuning procedure (mjfanalysis.benchmark_tuning) with a stand-in for a
tuning flight whose score is a known function of the gains: same budget for every law, the
defaults first, seeded points inside the search box, coordinate steps about the best."""
import math

import pytest

from mjfanalysis import benchmark_tuning as bt


def test_formation_table_writes_vector_gains_as_one_attribute():
    gains = {"k1": 3.0, "k2": 1.0, "lambda": 1.5, "alpha": 0.5}
    assert (bt.formation_table("super_twisting", gains)
            == '{plugin="super_twisting", k=[3, 1], lambda=1.5, alpha=0.5}')
    assert bt.formation_table("terminal_smc", {"beta": 0.1, "rho": 2.0}) == \
        '{plugin="terminal_smc", beta=0.10000000000000001, rho=2}'


def test_random_points_start_at_the_defaults_inside_the_box_and_repeat():
    defaults = bt.SEARCH_SPACE["vs_tracking"]
    points = bt.random_points(defaults, bt.Budget())
    assert len(points) == 8 and points[0] == defaults
    for p in points[1:]:
        for k, v in p.items():
            assert defaults[k] / 10 <= v <= defaults[k] * 10
    assert points == bt.random_points(defaults, bt.Budget())
    assert points != bt.random_points(defaults, bt.Budget(seed=2))


def test_coordinate_steps_cycle_through_the_gains():
    best = {"a": 1.0, "b": 4.0}
    assert bt.coordinate_step(best, 0) == {"a": 2.0, "b": 4.0}
    assert bt.coordinate_step(best, 1) == {"a": 0.5, "b": 4.0}
    assert bt.coordinate_step(best, 2) == {"a": 1.0, "b": 8.0}
    assert bt.coordinate_step(best, 3) == {"a": 1.0, "b": 2.0}
    assert bt.coordinate_step(best, 4) == {"a": 2.0, "b": 4.0}  # the cycle again


def test_a_failed_run_scores_infinity():
    assert bt.score({"failed": "collision", "rms_slot_error_m": 0.1}) == math.inf
    assert bt.score({"failed": None, "rms_slot_error_m": None}) == math.inf
    assert bt.score({"failed": None, "rms_slot_error_m": 0.25}) == 0.25


@pytest.mark.parametrize("law", sorted(bt.SEARCH_SPACE))
def test_every_law_gets_the_same_budget_and_the_best_point(monkeypatch, tmp_path, law):
    # Score: distance in log space to 3 x the defaults; gains above 8 x a default "crash".
    defaults = bt.SEARCH_SPACE[law]
    target = {k: 3.0 * v for k, v in defaults.items()}

    def fake_fly(mjformation, law_, gains, out, sets):
        if any(gains[k] > 8 * defaults[k] for k in gains):
            return math.inf
        return sum(math.log(gains[k] / target[k]) ** 2 for k in gains)

    monkeypatch.setattr(bt, "fly", fake_fly)
    result = bt.tune_law("mjformation", law, tmp_path, bt.Budget())
    assert result["runs"] == 40
    scores = [t["score"] for t in result["trace"]]
    assert result["best"]["score"] == min(scores)
    assert result["best"]["score"] < scores[0]  # better than the defaults
    assert result["formation"].startswith(f'{{plugin="{law}"')

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""A formation law written in Python, through the same runner, recorders and summary."""

import numpy as np
import pytest
from conftest import short
from consensus_law import consensus, consensus_agent

import mjformation


def cpp_consensus(exp2, shape, out, overrides=None):
    return mjformation.run(exp2, out=out, set={
        **(overrides or {}), "formation": {"plugin": "consensus_linear", "shape": shape}})


def test_python_consensus_flies_exp2_to_the_cpp_plugins_numbers(exp2, exp2_shape, tmp_path):
    # Given consensus_linear (C++) and its numpy re-implementation on Exp 2, 40 s
    cpp = cpp_consensus(exp2, exp2_shape, tmp_path / "cpp")
    py = mjformation.run(exp2, formation=consensus, out=tmp_path / "py")
    # Then sigma_f agrees to 1e-12 at every recorded sample, and the summary names the law
    assert cpp.complete and py.complete
    assert len(py.timeseries["sigma_f"]) == 4001
    assert np.max(np.abs(py.timeseries["sigma_f"] - cpp.timeseries["sigma_f"])) <= 1e-12
    assert py.summary["plugins"]["formation"] == {
        "name": "python", "attributes": {"law": "consensus_law.consensus", "period": "0"}}
    assert py.summary["plugin_report"]["python_calls"] == 40001
    # and the same recorders wrote the same columns
    assert list(py.timeseries) == list(cpp.timeseries)


def test_per_agent_python_consensus_flies_exp2_to_the_cpp_agents_numbers(exp2, exp2_shape,
                                                                          tmp_path):
    per_agent = {"execution.mode": "per_agent"}
    cpp = cpp_consensus(exp2, exp2_shape, tmp_path / "cpp", per_agent)
    py = mjformation.run(exp2, formation=mjformation.AgentLaw(consensus_agent),
                         out=tmp_path / "py")
    assert cpp.complete and py.complete
    assert py.summary["plugins"]["formation"]["name"] == "python_agent"
    assert py.summary["plugins"]["formation"]["attributes"]["law"] == \
        "consensus_law.consensus_agent"
    assert np.max(np.abs(py.timeseries["sigma_f"] - cpp.timeseries["sigma_f"])) <= 1e-12
    assert py.summary["network"] == cpp.summary["network"]


def test_an_agent_gets_only_its_own_state_and_its_messages(exp2):
    seen = {}

    def make(hood):
        def agent(t, me, messages, leader, offsets):
            seen[hood.follower] = (sorted(messages), leader is not None, me.shape, offsets.shape)
            return np.zeros(2)
        return agent

    sim = mjformation.Simulation(exp2, set=short(0.1), formation=mjformation.AgentLaw(make))
    sim.step(5)
    # Follower 1 (index 0) hears the leader and its ring neighbours 2 and 6
    assert seen[0] == ([1, 5], True, (13,), (6, 6))
    assert seen[3] == ([2, 4], False, (13,), (6, 6))


def test_a_sampled_law_is_called_once_per_period_and_held(exp2):
    calls = []

    def law(t, states, offsets, graph):
        calls.append(t)
        return np.full((6, 2), len(calls), dtype=float)

    sim = mjformation.Simulation(exp2, set=short(1.0),
                                 formation=mjformation.FormationLaw(law, period=0.05))
    sim.step(120)
    assert calls == pytest.approx([0.0, 0.05, 0.1])
    assert sim.setpoints[1, 0] == 3.0  # acc x of follower 1: the third sample, held


def test_an_exception_in_the_law_ends_the_run_incomplete_with_its_last_line(exp2, tmp_path):
    def law(t, states, offsets, graph):
        if t >= 0.5:
            return 1 / 0
        return np.zeros((6, 2))

    run = mjformation.run(exp2, set=short(2.0), formation=law, out=tmp_path / "r")
    assert run.summary["complete"] is False
    assert run.summary["error"].endswith("ZeroDivisionError: division by zero")
    assert run.summary["sim_time_s"] == pytest.approx(0.5)
    # everything recorded before the failing tick is kept (rows 0 .. 0.49 s)
    assert run.timeseries["t"][-1] == pytest.approx(0.49) and len(run.timeseries["t"]) == 50


def test_a_law_returning_the_wrong_shape_is_reported(exp2, tmp_path):
    run = mjformation.run(exp2, set=short(0.5), formation=lambda t, s, f, g: np.zeros((6, 3)),
                          out=tmp_path / "r")
    assert not run.complete
    # The shapes, not a truncated repr of the array
    assert ("the formation law returned an array of shape (6, 3), expected (6, 2): an "
            "(n_followers, 2) array") in run.summary["error"]


def test_a_nan_input_is_the_runners_non_finite_setpoint_failure(exp2, tmp_path):
    run = mjformation.run(exp2, set=short(0.5), formation=lambda t, s, f, g: np.full((6, 2), np.nan),
                          out=tmp_path / "r")
    assert not run.complete and "python" in run.summary["error"]


def test_a_law_returning_the_transposed_shape_is_reported(exp2, tmp_path):
    # (2, 6) has the element count of (6, 2) but not its meaning: refused, not read row-wise
    run = mjformation.run(exp2, set=short(0.5), formation=lambda t, s, f, g: np.zeros((2, 6)),
                          out=tmp_path / "r")
    assert not run.complete
    assert "returned an array of shape (2, 6), expected (6, 2)" in run.summary["error"]


def test_an_agent_law_returning_a_column_is_reported(exp2, tmp_path):
    run = mjformation.run(exp2, set=short(0.5), out=tmp_path / "r",
                          formation=mjformation.AgentLaw(lambda hood: lambda *a: np.zeros((2, 1))))
    assert not run.complete
    assert "returned an array of shape (2, 1), expected (2,): a (2,) array of accelerations" in \
        run.summary["error"]


def test_step_refuses_a_negative_count_and_stays_stopped_after_a_failure(exp2):
    def law(t, states, offsets, graph):
        if t >= 0.01:
            raise RuntimeError("the law gave up")
        return np.zeros((6, 2))

    sim = mjformation.Simulation(exp2, set=short(1.0), formation=law)
    with pytest.raises(ValueError, match="got -1"):
        sim.step(-1)
    assert sim.step_index == 0
    with pytest.raises(mjformation.SimulationError, match="the law gave up"):
        sim.step(50)
    stopped_at = sim.step_index
    # Then every later step raises again, naming the first failure, and nothing moves
    for _ in range(2):
        with pytest.raises(mjformation.SimulationError, match="stopped at t = 0.010 s"):
            sim.step(5)
    assert sim.step_index == stopped_at


def test_a_failed_run_warns_by_default_and_raises_when_asked(exp2, tmp_path):
    """A run that stops early is hard to miss: a RuntimeWarning with the reason, or RunFailed
    (with the Run, what was recorded kept) under raise_on_failure=True."""
    def bad(t, s, f, g):
        return np.zeros((6, 3))

    with pytest.warns(RuntimeWarning, match=r"stopped early at t = 0 s: .*shape \(6, 3\)"):
        run = mjformation.run(exp2, set=short(0.5), formation=bad, out=tmp_path / "w")
    assert not run.complete
    with pytest.raises(mjformation.RunFailed, match=r"expected \(6, 2\)") as failed:
        mjformation.run(exp2, set=short(0.5), formation=bad, out=tmp_path / "r",
                        raise_on_failure=True)
    assert failed.value.run.complete is False and (tmp_path / "r" / "summary.json").is_file()


def test_a_short_run_without_render_needs_no_snapshot_override(exp2):
    """render=False (the default) skips [render]'s checks, as the CLI's --no-render: exp2's
    snapshot times lie beyond a 0.2 s run, and only the duration is overridden."""
    run = mjformation.run(exp2, set={"run.duration": 0.2, "run.metric_window": [0.0, 0.2]})
    assert run.complete
    with pytest.raises(ValueError, match="snapshots"):
        mjformation.run(exp2, set={"run.duration": 0.2, "run.metric_window": [0.0, 0.2]},
                        render=True)


def test_a_period_below_the_smallest_normal_double_is_named_not_stod(exp2, tmp_path):
    """1e-320 s is a number (subnormal) of zero physics steps: refused for what it is, where
    std::stod threw "stod"."""
    law = mjformation.FormationLaw(lambda t, s, f, g: np.zeros((6, 2)), period=1e-320)
    with pytest.raises(ValueError, match=r"attribute 'period': T = 1e-320 s must be 0 \(every "
                                         r"physics step\) or a positive whole number of physics "
                                         r"steps of 0.001 s"):
        mjformation.run(exp2, set=short(0.1), formation=law, out=tmp_path / "r")


def test_a_law_returning_strings_is_refused_not_converted(exp2, tmp_path):
    """numpy would read the strings "0.0" as numbers: a law returns numbers or its run stops."""
    def law(t, states, offsets, graph):
        return np.full((6, 2), "0.0")

    with pytest.warns(RuntimeWarning, match="returned an array of <U3, expected numbers"):
        run = mjformation.run(exp2, set=short(0.1), formation=law, out=tmp_path / "r")
    assert not run.complete
    assert "the formation law returned an array of <U3, expected numbers" in run.summary["error"]

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The lower level of step(actions): each follower's collective thrust and body moments, its
attitude plugin bypassed, its actuator allocation turning the wrench into controls; and both
environments with action="thrust_moment"."""

import warnings

import numpy as np
import pytest

import mjformation
from conftest import short
from mjformation.envs import FormationEnv, FormationParallelEnv

THRUST_MOMENT = "thrust_moment"


def hovering(exp2, seconds=2.0):
    """A driven Exp 2 whose followers have held still under their attitude plugins for 0.5 s
    (zero acceleration commands): rotors spun up, level, at rest horizontally."""
    sim = mjformation.Simulation(exp2, set=short(seconds), driven=True, seed=0)
    sim.step(np.zeros((6, 3)), steps=500)
    return sim


def test_the_bounds_follow_from_the_vehicles_mass_and_actuator_ranges(exp2):
    sim = mjformation.Simulation(exp2, set=short(0.2), driven=True)
    low, high, hover = sim.thrust_moment_bounds()
    assert low.shape == high.shape == (6, 4) and hover.shape == (6,)
    # mjcf/quadrotor.xml: 1.5 kg; four rotors of ctrlrange [0, 7.066] N
    assert hover == pytest.approx(np.full(6, 1.5 * 9.81))
    assert low[:, 0] == pytest.approx(0.0) and high[:, 0] == pytest.approx(4 * 7.066)
    assert np.all(low[:, 1:] < 0) and np.allclose(low[:, 1:], -high[:, 1:])


def test_hover_thrust_from_a_hover_state_holds_the_follower_for_a_second(exp2):
    sim = hovering(exp2)
    _, _, hover = sim.thrust_moment_bounds()
    start = sim.states[1:, 0:3].copy()
    hold = np.column_stack([hover, np.zeros((6, 3))])
    for _ in range(1000):
        sim.step(hold, steps=1, action=THRUST_MOMENT)
    assert sim.time == pytest.approx(1.5)
    drift = np.linalg.norm(sim.states[1:, 0:3] - start, axis=1)
    assert drift.max() < 0.05, drift  # the altitude hold's last 2 cm/s of climb, no more
    # and without thrust the same followers fall
    sim = hovering(exp2)
    sim.step(np.zeros((6, 4)), steps=300, action=THRUST_MOMENT)
    assert np.all(sim.states[1:, 2] < start[:, 2] - 0.3)


def test_a_roll_moment_rolls_only_the_follower_it_is_given_to(exp2):
    sim = hovering(exp2)
    _, _, hover = sim.thrust_moment_bounds()
    wrench = np.column_stack([hover, np.zeros((6, 3))])
    wrench[2, 1] = 0.05  # N m about body x
    given = [i == 2 for i in range(6)]
    sim.step(wrench, steps=50, action=THRUST_MOMENT, given=given, commands=np.zeros((6, 3)))
    gyro = sim.states[1:, 10:13]
    # omega_x = tau / I_xx (t - tau_m (1 - exp(-t / tau_m))): the moment through the rotors'
    # first-order lag (tau_m = 0.025 s, I_xx = 0.029125 kg m^2, mjcf/quadrotor.xml), t = 0.05 s
    t, lag = 0.05, 0.025
    expected = 0.05 / 0.029125 * (t - lag * (1 - np.exp(-t / lag)))
    assert gyro[2, 0] == pytest.approx(expected, rel=0.03) and abs(gyro[2, 1]) < 1e-6
    assert np.abs(gyro[[0, 1, 3, 4, 5]]).max() < 1e-3  # the others' attitude plugins hold them


def test_the_same_seed_repeats_a_thrust_moment_flight(exp2):
    overrides = {**short(0.3), "sensors.preset": "typical"}
    sim = mjformation.Simulation(exp2, set=overrides, driven=True)
    rng = np.random.default_rng(7)
    low, high, _ = sim.thrust_moment_bounds()
    plan = [rng.uniform(0.6 * low + 0.4 * high, 0.4 * low + 0.6 * high) for _ in range(5)]

    def fly(seed):
        sim.reset(seed=seed)
        return np.array([sim.step(w, steps=20, action=THRUST_MOMENT)["own"] for w in plan])

    first = fly(2)
    assert np.array_equal(first, fly(2))
    assert not np.array_equal(first, fly(3))


def test_bad_wrenches_are_refused_naming_the_follower(exp2):
    sim = mjformation.Simulation(exp2, set=short(0.2), driven=True)
    with pytest.raises(ValueError, match=r"shape \(6, 3\), expected \(6, 4\)"):
        sim.step(np.zeros((6, 3)), action=THRUST_MOMENT)
    bad = np.zeros((6, 4))
    bad[4, 2] = np.nan
    with pytest.raises(ValueError, match="moment of follower 4"):
        sim.step(bad, action=THRUST_MOMENT)
    with pytest.raises(ValueError, match="acceleration.*thrust_moment"):
        sim.step(bad, action="torque")
    env = FormationParallelEnv(exp2, set=short(0.2), action=THRUST_MOMENT)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"uav3 \(follower 2\) has shape \(3,\)"):
        env.step({"uav3": np.zeros(3)})
    with pytest.raises(ValueError, match=r"uav2 \(follower 1\) is not finite"):
        env.step({"uav2": np.array([np.inf, 0, 0, 0])})


def test_a_point_mass_has_no_thrust_and_moments(exp2):
    overrides = {**short(0.2), "vehicles.model": "pointmass",
                 "attitude": {"plugin": "pointmass_direct"}}
    sim = mjformation.Simulation(exp2, set=overrides, driven=True)
    with pytest.raises(ValueError, match="pointmass.*3 actuators"):
        sim.step(np.zeros((6, 4)), action=THRUST_MOMENT)


def test_the_gymnasium_env_passes_its_checker_with_thrust_and_moments(exp2):
    from gymnasium.utils.env_checker import check_env

    env = FormationEnv(exp2, follower=1, set=short(0.3), action=THRUST_MOMENT)
    assert env.action_space.shape == (4,) and env.swarm.action_steps == 1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # unnormalised action Box, unbounded observations
        check_env(env, skip_render_check=True)
    env.reset(seed=0)
    _, reward, terminated, _, _ = env.step(env.hover_action())
    assert reward < 0 and not terminated


def test_the_parallel_env_passes_pettingzoos_api_test_with_thrust_and_moments(exp2):
    from pettingzoo.test import parallel_api_test

    env = FormationParallelEnv(exp2, set=short(0.3), action=THRUST_MOMENT)
    assert env.action_space("uav1").shape == (4,)
    parallel_api_test(env, num_cycles=20)


def test_partitioned_physics_flies_the_same_wrenches_bit_for_bit(exp2):
    """With [run] threads = 2 the followers' controls reach their partitions' models: the same
    flight as the single model's, some followers on wrenches and the others on their plugins."""
    def fly(threads):
        overrides = {**short(0.3), "run.threads": threads}
        sim = mjformation.Simulation(exp2, set=overrides, driven=True, seed=0)
        _, _, hover = sim.thrust_moment_bounds()
        wrench = np.column_stack([hover * 1.02, np.full((6, 3), 0.01)])
        given = [True, False, True, False, True, True]
        for _ in range(10):
            sim.step(wrench, steps=20, action=THRUST_MOMENT, given=given)
        return sim.states

    single = fly(1)
    assert np.array_equal(single, fly(2))
    # the same wrench from the same rest gives the four wrench-flown followers one body rate (to
    # rounding: their positions differ), about +x, +y, +z as the moments; the other two fly the law
    gyro = single[1:, 10:13]
    assert np.all(gyro[0] > 0) and np.allclose(gyro[[2, 4, 5]], gyro[0], rtol=1e-9, atol=0)
    assert not np.array_equal(gyro[0], gyro[1])

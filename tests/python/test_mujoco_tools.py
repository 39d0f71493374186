# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""MuJoCo's own tools on an exported Exp 2, through the `mujoco` package (docs/PLUGINS.md,
"Timing and state"): `mujoco.rollout` over threads, `mjd_transitionFD` against a finite
difference taken by hand over copies, and what rollout's `control` does. The controllers' state
lives in plugin_state, so each tool gives the bits of a plain mj_step loop. Short flights (1 s)."""


import mujoco
import mujoco.rollout
import numpy as np
import pytest

import mjformation

FULL = mujoco.mjtState.mjSTATE_FULLPHYSICS  # what rollout takes and returns (plugin_state too)


@pytest.fixture(scope="module")
def scene(exp2, tmp_path_factory):
    mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
    return mjformation.export(exp2, tmp_path_factory.mktemp("tools") / "exp2")


@pytest.fixture(scope="module")
def model(scene):
    return mujoco.MjModel.from_xml_path(str(scene))


def get_state(model, data) -> np.ndarray:
    state = np.empty(mujoco.mj_stateSize(model, FULL))
    mujoco.mj_getState(model, data, state, FULL)
    return state


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Every bit equal (plugin_state holds NaN for an actuator the plugin does not drive)."""
    return a.shape == b.shape and np.array_equal(a.view(np.int64), b.view(np.int64))


def serial(model, initial: np.ndarray, nstep: int) -> np.ndarray:
    """What rollout computes, as a plain loop: each state set on a new MjData, then mj_step."""
    out = np.empty((len(initial), nstep, initial.shape[1]))
    for b, state in enumerate(initial):
        data = mujoco.MjData(model)
        mujoco.mj_setState(model, data, state, FULL)
        for k in range(nstep):
            mujoco.mj_step(model, data)
            out[b, k] = get_state(model, data)
    return out


def flight(model, steps: int) -> np.ndarray:
    """The states of one plain flight from the start: row k after k steps."""
    data = mujoco.MjData(model)
    rows = [get_state(model, data)]
    for _ in range(steps):
        mujoco.mj_step(model, data)
        rows.append(get_state(model, data))
    return np.array(rows)


NBATCH, NSTEP, SPACING = 8, 200, 100


def test_rollout_over_two_threads_is_the_serial_loop_bit_for_bit(model):
    reference = flight(model, SPACING * NBATCH + NSTEP)
    starts = [SPACING * (b + 1) for b in range(NBATCH)]  # 0.1 .. 0.8 s
    initial = reference[starts]
    datas = [mujoco.MjData(model) for _ in range(2)]  # two threads, each its own MjData
    state, _ = mujoco.rollout.rollout(model, datas, initial, nstep=NSTEP)
    assert state.shape == (NBATCH, NSTEP, initial.shape[1])
    expected = serial(model, initial, NSTEP)
    assert same_bits(state, expected), np.nanmax(np.abs(state - expected))
    # ... and the serial loop continues the flight the states were taken from.
    for b, start in enumerate(starts):
        assert same_bits(expected[b], reference[start + 1:start + 1 + NSTEP]), b
    again, _ = mujoco.rollout.rollout(model, datas, initial, nstep=NSTEP)
    assert same_bits(again, state)
    # The controllers flew: the last state is not the first.
    assert np.nanmax(np.abs(state[:, -1] - initial)) > 1e-2


def random_controls(model, shape, seed: int = 3) -> np.ndarray:
    low, high = model.actuator_ctrlrange[:, 0], model.actuator_ctrlrange[:, 1]
    return np.random.default_rng(seed).uniform(low, high, size=(*shape, model.nu))


def test_rollouts_control_trims_the_swarms_rotors(model):
    """rollout's `control` is the rotors' trim (docs/PLUGINS.md, "Actuation"): zeros fly the
    free rollout's bits, other controls another flight."""
    initial = flight(model, 300)[[100, 300]]
    data = mujoco.MjData(model)
    free_state, free_sensors = mujoco.rollout.rollout(model, data, initial, nstep=150)
    zeros = np.zeros((2, 150, model.nu))
    state, sensors = mujoco.rollout.rollout(model, data, initial, zeros)
    assert same_bits(state, free_state) and same_bits(sensors, free_sensors)
    trimmed, _ = mujoco.rollout.rollout(model, data, initial, random_controls(model, (2, 150)))
    assert np.nanmax(np.abs(trimmed - free_state)) > 1e-4


def perturbed_step(model, data, dx: np.ndarray):
    """One mj_step of a copy of `data` with its (qpos, qvel, act) moved by dx in tangent space."""
    copy = mujoco.MjData(model)
    mujoco.mj_copyData(copy, model, data)
    nv = model.nv
    mujoco.mj_integratePos(model, copy.qpos, dx[:nv], 1.0)
    copy.qvel += dx[nv:2 * nv]
    copy.act += dx[2 * nv:]
    mujoco.mj_step(model, copy)
    return copy.qpos.copy(), np.concatenate([copy.qvel, copy.act])


def column_by_hand(model, data, j: int, eps: float) -> np.ndarray:
    """A's column j by centred differences over copies: (x'(x + eps e_j) - x'(x - eps e_j)) /
    (2 eps), positions differenced on the manifold (mj_differentiatePos)."""
    nx = 2 * model.nv + model.na
    dx = np.zeros(nx)
    dx[j] = eps
    qpos_plus, rest_plus = perturbed_step(model, data, dx)
    qpos_minus, rest_minus = perturbed_step(model, data, -dx)
    dq = np.zeros(model.nv)
    mujoco.mj_differentiatePos(model, dq, 2 * eps, qpos_minus, qpos_plus)
    return np.concatenate([dq, (rest_plus - rest_minus) / (2 * eps)])


def test_transition_fd_is_the_finite_difference_by_hand(model):
    """At t = 1 s (a tick of the formation law, period 0.05 s): A from mjd_transitionFD is the
    closed loop's, the columns a user gets by stepping perturbed copies. C is asked for: without C
    or D MuJoCo skips the sensors in the perturbed steps, and the controllers, which read them,
    see the unperturbed ones (docs/PLUGINS.md)."""
    data = mujoco.MjData(model)
    for _ in range(1000):
        mujoco.mj_step(model, data)
    nv, na, nu = model.nv, model.na, model.nu
    nx = 2 * nv + na
    eps = 1e-6
    A, B = np.zeros((nx, nx)), np.zeros((nx, nu))
    C = np.zeros((model.nsensordata, nx))
    mujoco.mjd_transitionFD(model, data, eps, True, A, B, C, None)
    dof = model.jnt_dofadr[model.body("uav1_vehicle").jntadr[0]]  # a follower's free joint
    act = model.actuator_actadr[model.actuator("uav1_rotor0").id]
    columns = {"x": dof, "vx": nv + dof, "wx": nv + dof + 3, "rotor0": 2 * nv + act}
    for name, j in columns.items():
        by_hand = column_by_hand(model, data, j, eps)
        # Both sides evaluate the same steps: they differ by rounding, amplified by 1/eps.
        assert np.allclose(A[:, j], by_hand, rtol=0, atol=1e-6), (
            name, np.abs(A[:, j] - by_hand).max())
    # The motor lag's own diagonal, 1 - h / tau (the controllers do not read act); ticking at
    # every evaluation used to make it -3.21.
    tau = model.actuator_dynprm[model.actuator("uav1_rotor0").id, 0]
    assert A[2 * nv + act, 2 * nv + act] == pytest.approx(1 - model.opt.timestep / tau, rel=1e-8)
    # B: a rotor's trim moves only its own motor lag within the step, by h / tau.
    ctrl = model.actuator_ctrladr[model.actuator("uav1_rotor0").id]
    column = B[:, ctrl]
    assert np.flatnonzero(column).tolist() == [2 * nv + act]
    assert column[2 * nv + act] == pytest.approx(model.opt.timestep / tau, rel=1e-6)


@pytest.mark.parametrize("experiment, extra", [
    ("experiments/benchmark/b06_gusty_wind.toml", {}),
    ("experiments/exp2.toml", {"vehicles.rotor_model": "wrench"}),
], ids=["wind", "wrench"])
def test_transition_fd_with_the_forces_besides_the_actuators(source, tmp_path, experiment, extra):
    """[wind]'s drag and the wrench rotor model's wrenches, added by the plugin into qfrc_passive
    (docs/PLUGINS.md, "Forces besides the actuators"): A's position and velocity columns are the
    differences by hand over copies (the drag of a perturbed velocity included), and B's columns,
    differenced without the velocity stage, see each force once."""
    mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
    scene = mjformation.export(source / experiment, tmp_path / "scene", set=extra)
    model = mujoco.MjModel.from_xml_path(str(scene))
    data = mujoco.MjData(model)
    for _ in range(500):
        mujoco.mj_step(model, data)
    nv, nx, nu = model.nv, 2 * model.nv + model.na, model.nu
    eps = 1e-6
    A, B = np.zeros((nx, nx)), np.zeros((nx, nu))
    C = np.zeros((model.nsensordata, nx))
    mujoco.mjd_transitionFD(model, data, eps, True, A, B, C, None)
    dof = model.jnt_dofadr[model.body("uav1_vehicle").jntadr[0]]
    for name, j in {"x": dof, "vx": nv + dof, "vz": nv + dof + 2, "wx": nv + dof + 3}.items():
        by_hand = column_by_hand(model, data, j, eps)
        assert np.allclose(A[:, j], by_hand, rtol=0, atol=1e-6), (
            name, np.abs(A[:, j] - by_hand).max())
    if extra:  # the wrench scene's one actuator has no force: its column is zero, to the bit
        assert model.nu == 1 and not B.any()
    else:  # a rotor's trim moves its own motor lag only, by h / tau (the drag is not in it)
        rotor = model.actuator("uav1_rotor0").id
        act = model.actuator_actadr[rotor]
        column = B[:, model.actuator_ctrladr[rotor]]
        assert np.flatnonzero(column).tolist() == [2 * nv + act]
        tau = model.actuator_dynprm[rotor, 0]
        assert column[2 * nv + act] == pytest.approx(model.opt.timestep / tau, rel=1e-6)

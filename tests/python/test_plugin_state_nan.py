# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""An exported Exp 2 flown by the `mujoco` package: its plugin_state holds NaN where a quantity is
undefined, so identical states compare equal with equal_nan=True and not otherwise
(docs/PYTHON.md, "Saving and restoring a state"; the layout: docs/PLUGINS.md, "Timing and
state")."""

import mujoco
import mujoco.rollout
import numpy as np
import pytest

import mjformation

INTEGRATION = mujoco.mjtState.mjSTATE_INTEGRATION  # holds mjSTATE_PLUGIN
HEADER = 5  # layout, k, the held step, the blocks' mark, the forces' mark
BUS = 14  # a vehicle's setpoints: acc 3, pos 3, vel 3, yaw, sliding 2


@pytest.fixture(scope="module")
def model(exp2, tmp_path_factory):
    # `import mjformation` registered the native plugins with the engine `mujoco` shares
    scene = mjformation.export(exp2, tmp_path_factory.mktemp("nan") / "exp2")
    return mujoco.MjModel.from_xml_path(str(scene))


def get_state(model, data) -> np.ndarray:
    state = np.empty(mujoco.mj_stateSize(model, INTEGRATION))
    mujoco.mj_getState(model, data, state, INTEGRATION)
    return state


def test_plugin_state_holds_nan_where_a_quantity_is_undefined(model):
    data = mujoco.MjData(model)
    held = slice(HEADER, HEADER + model.nu)  # each actuator's held control
    # Before the first tick no control is held: NaN, and nothing else is
    assert np.isnan(data.plugin_state[held]).all()
    assert np.isnan(data.plugin_state).sum() == model.nu == 28
    for _ in range(3):
        mujoco.mj_step(model, data)
    # From then on the controls are held; the leader's sliding variables (no formation law
    # drives it) stay NaN on the setpoint bus, which follows them in Exp 2 (no force block),
    # the leader's row first
    assert np.isfinite(data.plugin_state[held]).all()
    bus = HEADER + model.nu
    assert np.flatnonzero(np.isnan(data.plugin_state)).tolist() == [bus + 10, bus + 11]
    assert len(data.plugin_state) == 180


def test_identical_states_compare_equal_only_with_equal_nan(model):
    data = mujoco.MjData(model)
    for _ in range(3):
        mujoco.mj_step(model, data)
    copy = mujoco.MjData(model)
    mujoco.mj_copyData(copy, model, data)
    for a, b in ((data.plugin_state, copy.plugin_state),
                 (get_state(model, data), get_state(model, copy))):
        assert not np.array_equal(a, b) and not np.isfinite(a).all()
        assert np.array_equal(a, b, equal_nan=True)
        assert np.array_equal(a.view(np.int64), b.view(np.int64))  # bit for bit
    # mujoco.rollout's states carry plugin_state too: two rollouts of one start agree the same way
    full = mujoco.mjtState.mjSTATE_FULLPHYSICS
    start = np.empty((1, mujoco.mj_stateSize(model, full)))
    mujoco.mj_getState(model, data, start[0], full)
    first, _ = mujoco.rollout.rollout(model, mujoco.MjData(model), start, nstep=2)
    second, _ = mujoco.rollout.rollout(model, mujoco.MjData(model), start, nstep=2)
    assert not np.array_equal(first, second)
    assert np.array_equal(first, second, equal_nan=True)

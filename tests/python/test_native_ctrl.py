# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""ctrl of a driven rotor is a trim on the controllers' command (docs/PLUGINS.md, "Actuation"):
mujoco.rollout's `control` acts on an exported scene, and zero controls are plain mj_step."""

import mujoco
import numpy as np
import pytest
from mujoco import rollout

import mjformation

STEPS = 300  # 0.6 s of Exp 2


@pytest.fixture(scope="module")
def scene(exp2, tmp_path_factory):
    mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
    return mjformation.export(exp2, tmp_path_factory.mktemp("ctrl") / "exp2")


def test_rollout_control_trims_one_rotor(scene):
    model = mujoco.MjModel.from_xml_path(str(scene))
    data = mujoco.MjData(model)
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    initial = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, initial, spec)
    zeros = np.zeros((STEPS, model.nu))
    trimmed = zeros.copy()
    rotor = model.actuator("uav1_rotor0").id
    trimmed[:, model.actuator_ctrladr[rotor]] = 0.5  # N on one rotor of uav1
    flown = rollout.rollout(model, data, initial, np.stack([zeros, trimmed]))[0]

    plain = mujoco.MjData(model)
    expected = np.empty((STEPS, initial.size))
    for k in range(STEPS):
        mujoco.mj_step(model, plain)
        mujoco.mj_getState(model, plain, expected[k], spec)
    # Zero controls: the plain flight, every bit (plugin_state holds NaNs, so bytes compared).
    assert flown[0].tobytes() == expected.tobytes()

    body = model.body("uav1_vehicle").id
    qpos = 1 + model.jnt_qposadr[model.body_jntadr[body]]  # the state's first entry is time
    moved = np.abs(flown[1, -1, qpos:qpos + 3] - flown[0, -1, qpos:qpos + 3]).max()
    assert moved > 1e-4, moved

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""An exported scene attached into a user's world with the `mujoco` package's MjSpec.attach
keeps its controllers, with MuJoCo's default prefix ("/"), none, or two copies side by side
(docs/PLUGINS.md, "Attach into your world")."""

import mujoco
import numpy as np
import pytest

import mjformation

WORLD = """<mujoco><option timestep="0.001"/><worldbody>
  <geom name="floor" type="plane" size="60 60 0.1"/>
  <body name="crate" pos="40 40 0.5"><geom type="box" size="0.5 0.5 0.5"/></body>
</worldbody></mujoco>"""
STEPS = 1000  # 1 s of Exp 2


@pytest.fixture(scope="module")
def scene(exp2, tmp_path_factory):
    mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
    return mjformation.export(exp2, tmp_path_factory.mktemp("attach") / "exp2")


def attached(scene, prefixes):
    world = mujoco.MjSpec.from_string(WORLD)
    for prefix in prefixes:
        child = mujoco.MjSpec.from_file(str(scene))
        frame = world.worldbody.add_frame()
        if prefix is None:
            world.attach(child, frame=frame)  # MuJoCo's default prefix, "/"
        else:
            world.attach(child, prefix=prefix, frame=frame)
    return world.compile()


def vehicles(model, data, prefix):
    return np.array([data.qpos[model.joint(f"{prefix}uav{i}_root").qposadr[0]:][:7]
                     for i in range(7)])


@pytest.mark.parametrize("prefixes", [[None], [""], ["a_", "b_"]])
def test_attached_swarm_flies_the_unattached_scenes_bits(scene, prefixes):
    plain = mujoco.MjModel.from_xml_path(str(scene))
    model = attached(scene, prefixes)
    assert model.nplugin == len(prefixes)
    data, reference = mujoco.MjData(model), mujoco.MjData(plain)
    start = vehicles(plain, reference, "")
    for _ in range(STEPS):
        mujoco.mj_step(model, data)
        mujoco.mj_step(plain, reference)
    expected = vehicles(plain, reference, "")
    for prefix in prefixes:
        # Only renamed and beside bodies no drone touches: the same operations, the same bits.
        assert np.array_equal(vehicles(model, data, "/" if prefix is None else prefix), expected)
    assert np.abs(expected[:, 2] - start[:, 2]).max() < 0.05  # held altitude, did not fall
    assert np.abs(expected[:, 0:2] - start[:, 0:2]).max() > 0.5  # and flew the formation


def test_attached_world_saved_and_reloaded_keeps_its_controllers(scene):
    world = mujoco.MjSpec.from_string(WORLD)
    world.attach(mujoco.MjSpec.from_file(str(scene)), prefix="a/",
                 frame=world.worldbody.add_frame())
    model = world.compile()
    # Saved beside the exported files it names (relative paths), the references saved too.
    saved = scene.parent / "saved_world.xml"
    saved.write_text(world.to_xml())
    reloaded = mujoco.MjModel.from_xml_path(str(saved))
    assert reloaded.nplugin == 1
    data, again = mujoco.MjData(model), mujoco.MjData(reloaded)
    for _ in range(STEPS // 2):
        mujoco.mj_step(model, data)
        mujoco.mj_step(reloaded, again)
    assert np.array_equal(again.qpos, data.qpos)
    assert np.abs(vehicles(reloaded, again, "a/")[:, 2] - 5.0).max() < 0.05  # at Exp 2's altitude

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""One engine per process, and a composed scene that flies in stock MuJoCo.

Run by the project environment's interpreter (.venv, which holds the pinned `mujoco` package):
- `import mujoco, mjformation` in either order maps one libmujoco file, and both report it;
- the scene.xml the runner composes, loaded by the `mujoco` package alone and driven with the
  runner's own controls, steps to the runner's state over its first 100 physics steps.
"""
import subprocess
import sys

import numpy as np
import pytest

from conftest import short

mujoco = pytest.importorskip("mujoco", reason="needs the project environment's mujoco (.venv)")
import mjformation  # noqa: E402

PROBE = """
import {first}, {second}
import mjformation, mujoco
maps = {{line.split()[-1] for line in open("/proc/self/maps") if "libmujoco.so" in line}}
print(len(maps), maps.pop(), mujoco.mj_versionString(), mjformation.engine()["version"],
      mjformation.engine()["library"])
"""


@pytest.mark.parametrize("first,second", [("mujoco", "mjformation"), ("mjformation", "mujoco")])
def test_mujoco_and_mjformation_share_one_engine(first, second):
    out = subprocess.run([sys.executable, "-c", PROBE.format(first=first, second=second)],
                         capture_output=True, text=True, check=True).stdout.split()
    n_libraries, mapped, mujoco_version, our_version, our_library = out
    assert n_libraries == "1", f"libmujoco mapped from {n_libraries} files"
    assert mujoco_version == our_version
    assert mujoco.mj_versionString() in mjformation.version()
    # Both resolve to the same file (the path may be spelled through a symlink).
    import os
    assert os.path.realpath(our_library) == os.path.realpath(mapped)


def test_engine_names_the_library_and_its_hash():
    import hashlib
    engine = mjformation.engine()
    assert engine["version"] == mujoco.mj_versionString()
    with open(engine["library"], "rb") as f:
        assert engine["sha256"] == hashlib.sha256(f.read()).hexdigest()


def test_the_composed_scene_steps_in_stock_mujoco_as_in_the_runner(exp2):
    sim = mjformation.Simulation(exp2, set=short(0.2))
    model = mujoco.MjModel.from_xml_string(sim.scene_xml)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert model.nu == sim.controls.size
    worst = 0.0
    for _ in range(100):
        data.ctrl[:] = np.asarray(sim.controls).ravel()
        mujoco.mj_step(model, data)
        sim.step(1)
        ours = np.asarray(sim.states)
        # Position and velocity of every vehicle (its free joint: 7 qpos, 6 qvel).
        theirs_pos = data.qpos.reshape(-1, 7)[:, :3]
        theirs_vel = data.qvel.reshape(-1, 6)[:, :3]
        worst = max(worst, np.abs(theirs_pos - ours[:, 0:3]).max(),
                    np.abs(theirs_vel - ours[:, 3:6]).max())
    assert worst < 1e-9, f"stock MuJoCo left the runner's trajectory by {worst:g}"

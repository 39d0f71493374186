# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Our geometric attitude controller on your own drone (my_drone.xml), in plain MuJoCo.

    python fly_my_drone.py [--viewer]

The controller is the native plugin `mjformation.attitude` of libmjformation_mujoco.so; the
scene names it with its configuration, and MuJoCo does the rest: mj_step flies the drone.
"""
import argparse
import sys
from pathlib import Path

import mujoco
import numpy as np

import mjformation


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--viewer", action="store_true", help="open MuJoCo's viewer")
    parser.add_argument("--seconds", type=float, default=15.0)
    args = parser.parse_args()
    mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
    model = mujoco.MjModel.from_xml_path(str(Path(__file__).with_name("my_drone.xml")))
    data = mujoco.MjData(model)
    if args.viewer:
        from mujoco import viewer
        viewer.launch(model, data)
        return 0
    while data.time < args.seconds:
        mujoco.mj_step(model, data)
    position = data.body("quad").xpos
    error = np.linalg.norm(position - np.array([1.0, -0.5, 1.5]))
    print(f"t = {data.time:.2f} s: drone at {np.round(position, 3)}, {error:.3f} m from the "
          "held point (1, -0.5, 1.5)")
    return 0 if error < 0.01 else 1


if __name__ == "__main__":
    sys.exit(main())

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Fly an exported experiment in plain MuJoCo, headless (or in MuJoCo's viewer), and compute
the formation error sigma_f of eq. (68) from mjData alone.

    mjformation export experiments/exp2.toml -o exp2_native
    python fly_exported.py exp2_native/scene.xml [--plot sigma_f.png] [--viewer]

sigma_f = || X - F - 1_N (x) x_0 ||, over the followers' positions and velocities in x and y:
X from the vehicles' sensors (uav<i>_pos, uav<i>_vel in data.sensordata), x_0 the leader's
(uav0_), F the desired offsets f_i(t) of [formation.shape] (a circle here: Definition 1 with
the parameters the scene carries in the plugin's "formation" configuration).
"""
import argparse
import math
import os
import sys
import tomllib
import xml.etree.ElementTree as ET

import mujoco
import numpy as np

import mjformation


def circle_shape(scene_path: str) -> dict:
    """The [formation.shape] table the exported scene carries (<config key="formation">)."""
    for config in ET.parse(scene_path).getroot().iter("config"):
        if config.get("key") == "formation":
            shape = tomllib.loads("f = {" + config.get("value") + "}")["f"]["shape"]
            if shape.get("type", "circle") != "circle":
                raise SystemExit(f"fly_exported.py: {scene_path}: the formation shape is "
                                 f"'{shape.get('type')}'; this example computes F for a circle only")
            return shape
    raise SystemExit(f"fly_exported.py: {scene_path}: no mjformation.swarm formation configuration; "
                     "pass a scene written by `mjformation export`")


def offsets(shape: dict, n: int, t: float) -> np.ndarray:
    """f_i(t) for followers i = 1..n: (px, py, vx, vy) rows."""
    r, w = shape["radius"], shape["omega"]
    out = np.empty((n, 4))
    for i in range(n):
        theta = w * t + shape.get("phase0", 0.0) + i * shape.get("phase_step", 0.0)
        c, s = math.cos(theta), math.sin(theta)
        out[i] = (r * c, r * s, -r * w * s, r * w * c)
    return out


def sigma_f(model, data, shape: dict, n_followers: int) -> float:
    """eq. (68) from the sensors of the data's current step."""
    def pv(i):
        p = model.sensor(f"uav{i}_pos").adr[0]
        v = model.sensor(f"uav{i}_vel").adr[0]
        return np.array([data.sensordata[p], data.sensordata[p + 1],
                         data.sensordata[v], data.sensordata[v + 1]])
    leader = pv(0)
    followers = np.array([pv(i) for i in range(1, n_followers + 1)])
    deviation = followers - offsets(shape, n_followers, data.time) - leader
    return float(np.sqrt(np.sum(deviation ** 2)))


def fly(scene_path: str, seconds: float, every: float = 0.1):
    """(times, sigma_f) sampled every `every` s over `seconds` of flight."""
    mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
    model = mujoco.MjModel.from_xml_path(scene_path)
    data = mujoco.MjData(model)
    shape = circle_shape(scene_path)
    n = sum(1 for i in range(model.nsensor) if model.sensor(i).name.endswith("_pos")) - 1
    stride = round(every / model.opt.timestep)
    times, sigma = [], []
    for k in range(round(seconds / model.opt.timestep) + 1):
        if k % stride == 0:
            mujoco.mj_forward(model, data)  # this step's sensors (the plugin holds its tick)
            times.append(data.time)
            sigma.append(sigma_f(model, data, shape, n))
        mujoco.mj_step(model, data)
    return np.array(times), np.array(sigma)


def fail(message: str) -> SystemExit:
    """One line on stderr naming what is wrong and what to do; exit status 1."""
    return SystemExit(f"fly_exported.py: {message}")


def check_arguments(args) -> None:
    """Refuses what would otherwise end in a traceback after minutes of flight."""
    if not os.path.isfile(args.scene):
        raise fail(f"{args.scene}: no such file; write one with "
                   "`mjformation export EXPERIMENT.toml -o DIR` and pass DIR/scene.xml")
    try:
        ET.parse(args.scene)
    except ET.ParseError as error:
        raise fail(f"{args.scene}: line {error.position[0]}: not an XML file ({error}); "
                   "pass the scene.xml `mjformation export` wrote") from None
    if not (math.isfinite(args.seconds) and args.seconds > 0):
        raise fail(f"--seconds {args.seconds:g}: give a positive number of seconds")
    if args.plot:
        folder = os.path.dirname(os.path.abspath(args.plot))
        if not os.path.isdir(folder) or not os.access(folder, os.W_OK):
            raise fail(f"--plot {args.plot}: cannot write into {folder}; name a writable file")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", help="scene.xml written by `mjformation export`")
    parser.add_argument("--seconds", type=float, default=40.0)
    parser.add_argument("--plot", help="write sigma_f(t) to this image")
    parser.add_argument("--viewer", action="store_true", help="open MuJoCo's viewer instead")
    args = parser.parse_args()
    check_arguments(args)
    try:
        return fly_and_report(args)
    except ValueError as error:  # MuJoCo's compiler and the plugins report through ValueError
        raise fail(f"{args.scene}: MuJoCo refused the scene: {str(error).splitlines()[0]}") from None


def fly_and_report(args) -> int:
    """The viewer, or a headless flight with its sigma_f line and optional plot."""
    if args.viewer:
        from mujoco import viewer
        mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
        model = mujoco.MjModel.from_xml_path(args.scene)
        viewer.launch(model, mujoco.MjData(model))
        return 0
    times, sigma = fly(args.scene, args.seconds)
    print(f"sigma_f(0) = {sigma[0]:.4g}, sigma_f({times[-1]:.1f} s) = {sigma[-1]:.4g}")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.semilogy(times, sigma)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("sigma_f, eq. (68)")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())

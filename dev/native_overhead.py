# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The exported scene in stock MuJoCo beside `mjformation run --no-render`, in one command
(docs/PLUGINS.md, "What the state costs").

For each experiment: (a) the runner's stepping loop, as `run --no-render` times it (summary.json
timing.wall_time_s: the tick, actuation, mj_step and recording, no composition, no rendering);
(b) the exported scene stepped for the same step count, one thread: by a C program that calls
mj_step and nothing else (`--stepper c`, tests/bench/scene_step_time.cc, the default), by
`mujoco.rollout` (MuJoCo's C loop, which also records the full state after every step) or by
mj_step called from Python (about a microsecond per call of its own): the native plugin's tick
with its state round trip through plugin_state every step. Runs alternate (a, b, a, b, ...) so that a change in the machine's load
hits both; the median of each is reported with the ratio b / a and the native path's extra cost
per step and vehicle, state handling included. The load (os.getloadavg) is printed beside it.

    PYTHONPATH=build/python .venv/bin/python dev/native_overhead.py [--repeats 5] [--duration 10]
        [--cases exp2,exp2_pointmass,b05,b06,exp2_wrench] [--stepper c|rollout|mj_step]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import mujoco
import mujoco.rollout
import numpy as np

import mjformation

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "exp2": ("experiments/exp2.toml", {}),
    "exp2_pointmass": ("experiments/exp2.toml",
                       {"vehicles.model": "pointmass", "attitude": {"plugin": "pointmass_direct"}}),
    # GNSS-grade sensors through kf_ins: the estimators' declared state in the round trip.
    "b05": ("experiments/benchmark/b05_gnss_kf.toml", {}),
    # Per-agent execution over a lossy network: the links' streams and queues in plugin_state.
    "b13": ("experiments/benchmark/b13_lossy_network.toml", {}),
    # Wind with Dryden turbulence: the wind field's streams in plugin_state, its drag added into
    # qfrc_passive at every evaluation.
    "b06": ("experiments/benchmark/b06_gusty_wind.toml", {}),
    # The wrench rotor model: the rotors' wrenches added by the plugin (motor lags in
    # plugin_state) instead of by MuJoCo's actuators.
    "exp2_wrench": ("experiments/exp2.toml", {"vehicles.rotor_model": "wrench"}),
}


def runner_seconds(experiment: Path, overrides: dict, out: Path) -> tuple[float, int, int]:
    """The runner's stepping loop (run --no-render): wall seconds, steps, vehicles."""
    run = mjformation.run(experiment, set=overrides, out=out, overwrite=True, render=False,
                          raise_on_failure=True)
    summary = json.loads((out / "summary.json").read_text())
    del run
    return summary["timing"]["wall_time_s"], summary["steps"], summary["n_followers"] + 1


STEP_TIME = ROOT / "build" / "tests" / "bench" / "scene_step_time"


def native_seconds(model: mujoco.MjModel, scene: Path, steps: int, stepper: str) -> float:
    """The exported scene from its initial state, one thread: a C loop of mj_step, mujoco.rollout
    (which also records the full state, plugin_state included, after every step) or mj_step
    called from Python."""
    if stepper == "c":
        out = subprocess.run([str(STEP_TIME), mjformation.native_plugin_library(), str(scene),
                              str(steps)], check=True, capture_output=True, text=True)
        return float(out.stdout)
    data = mujoco.MjData(model)
    full = mujoco.mjtState.mjSTATE_FULLPHYSICS
    initial = np.empty((1, mujoco.mj_stateSize(model, full)))
    mujoco.mj_getState(model, data, initial[0], full)
    start = time.perf_counter()
    if stepper == "rollout":
        mujoco.rollout.rollout(model, data, initial, nstep=steps)
    else:
        for _ in range(steps):
            mujoco.mj_step(model, data)
    return time.perf_counter() - start


def measure(name: str, repeats: int, duration: float, scratch: Path, stepper: str) -> dict:
    experiment, extra = CASES[name]
    overrides = {"run.duration": duration, "run.metric_window": [0.0, duration],
                 "render.snapshots": [], **extra}
    scene = mjformation.export(ROOT / experiment, scratch / f"{name}_scene", overwrite=True,
                               set=overrides)
    model = mujoco.MjModel.from_xml_path(str(scene))
    runner, native = [], []
    for _ in range(repeats):
        seconds, steps, vehicles = runner_seconds(ROOT / experiment, overrides,
                                                  scratch / f"{name}_run")
        runner.append(seconds)
        native.append(native_seconds(model, scene, steps, stepper))
    a, b = statistics.median(runner), statistics.median(native)
    return {"case": name, "steps": steps, "vehicles": vehicles, "runner_s": a, "native_s": b,
            "ratio": b / a, "extra_us_per_vehicle_step": 1e6 * (b - a) / (steps * vehicles),
            "state_doubles": model.npluginstate, "runner_all": runner, "native_all": native}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="runs of each side (median)")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds per run")
    parser.add_argument("--cases", default="exp2,exp2_pointmass", help="comma-separated: " +
                        ", ".join(CASES))
    parser.add_argument("--stepper", choices=("c", "rollout", "mj_step"), default="c",
                        help="how the exported scene is stepped: a C loop of mj_step (" +
                        str(STEP_TIME.relative_to(ROOT)) + "), mujoco.rollout (its C loop; it "
                        "records the full state every step, which grows with plugin_state) or "
                        "mj_step from Python (about a microsecond per call of its own)")
    args = parser.parse_args()
    if args.stepper == "c" and not STEP_TIME.is_file():
        parser.error(f"{STEP_TIME} is not built: cmake --build build --target scene_step_time")
    mujoco.mj_loadPluginLibrary(mjformation.native_plugin_library())
    print(f"load before: {os.getloadavg()[0]:.2f}  {time.strftime('%Y-%m-%d %H:%M')}")
    with tempfile.TemporaryDirectory(prefix="mjformation_overhead_") as scratch:
        for name in args.cases.split(","):
            r = measure(name, args.repeats, args.duration, Path(scratch), args.stepper)
            print(f"{r['case']:15s} {r['vehicles']} vehicles, {r['steps']} steps: "
                  f"run --no-render {r['runner_s']:.3f} s, exported + {args.stepper} "
                  f"{r['native_s']:.3f} s, ratio {r['ratio']:.3f}, native extra "
                  f"{r['extra_us_per_vehicle_step']:+.3f} us per vehicle-step; plugin_state "
                  f"{r['state_doubles']} doubles", flush=True)
    print(f"load after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Where a step of N quadrotors goes in MuJoCo alone, with and without their rotor actuators.

    .venv/bin/python dev/transmission_cost.py [N]      (default 200)

Composes N copies of mjcf/quadrotor.xml with mjSpec (contacts off, Euler, 1 ms), steps each
model 100 times with constant controls and prints steps/s and MuJoCo's own stage timers
(mjData.timer). The difference between the two models is the rotors' site transmissions:
docs/PERFORMANCE.md, "What the figures mean" (use the wrench rotor model for large swarms).
"""
import sys
import time
from pathlib import Path

import mujoco

ROOT = Path(__file__).resolve().parents[1]


def swarm(n, with_actuators):
    world = mujoco.MjSpec.from_file(str(ROOT / "mjcf/scene.xml"))
    world.option.timestep = 0.001
    world.option.integrator = mujoco.mjtIntegrator.mjINT_EULER
    world.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    for i in range(n):
        vehicle = mujoco.MjSpec.from_file(str(ROOT / "mjcf/quadrotor.xml"))
        if not with_actuators:
            for actuator in list(vehicle.actuators):
                vehicle.delete(actuator)
        frame = world.worldbody.add_frame(pos=[2.0 * (i % 20), 2.0 * (i // 20), 5.0])
        frame.attach_body(vehicle.body("vehicle"), f"uav{i}_", "")
    return world.compile()


def measure(model, steps=100):
    data = mujoco.MjData(model)
    data.ctrl[:] = 2.0
    mujoco.mj_forward(model, data)
    start = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, data)
    rate = steps / (time.perf_counter() - start)
    stages = {mujoco.mjtTimer(k).name: t.duration / t.number * 1e3
              for k, t in enumerate(data.timer) if t.number}
    return rate, stages


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    for with_actuators in (True, False):
        model = swarm(n, with_actuators)
        rate, stages = measure(model)
        print(f"{n} quadrotors, {model.nu} actuators, nv {model.nv}: {rate:,.0f} steps/s; "
              f"step {stages['mjTIMER_STEP']:.3f} ms, position kinematics "
              f"{stages['mjTIMER_POS_KINEMATICS']:.3f} ms, actuation "
              f"{stages.get('mjTIMER_ACTUATION', 0):.3f} ms")


if __name__ == "__main__":
    main()

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Environment steps per second of mjformation.envs.FormationParallelEnv (docs/PYTHON.md,
"Environments"): Exp 2 resized to 7 and 49 followers (a ring graph, the leader heard by
follower 1, the default start ring, the formation circle widened so slots stay 1.5 m apart, as
`mjformation bench` resizes it), every agent flying the SMC law's own command, which the
environment hands out (law_actions). Each environment step holds the command for
`action_steps` physics steps of 1 ms (50: the law's sample period T = 0.05 s). Then the lower
level (action="thrust_moment"): every agent its hover thrust and zero moments, one physics step
per environment step, the attitude plugins bypassed.

    PYTHONPATH=build/python .venv/bin/python examples/python/env_speed.py [--seconds 5]
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

from mjformation.envs import FormationParallelEnv

EXP2 = Path(__file__).resolve().parents[2] / "experiments/exp2.toml"


def resized(followers: int, duration: float) -> dict:
    ring = [[i + 1, (i + 1) % followers + 1] for i in range(followers)]
    ring += [[b, a] for a, b in ring]
    return {
        "run.duration": duration, "run.metric_window": [0.0, duration], "render.snapshots": [],
        "vehicles": {"model": "quadrotor", "followers": followers, "altitude": 5.0,
                     "leader_start": [20.0, 0.0]},
        "topology": {"leader_links": [1], "edges": ring},
        "formation.shape.radius": max(10.0, 1.5 * followers / (2 * math.pi)),
        "formation.shape.phase_step": 2 * math.pi / followers,
    }


def measure(followers: int, action_steps: int, seconds: float,
            action: str = "acceleration") -> tuple[float, float]:
    """(environment steps per second, simulated seconds per wall second)."""
    env = FormationParallelEnv(EXP2, set=resized(followers, 1000.0), action_steps=action_steps,
                               action=action)
    env.reset(seed=0)
    actions = env.law_actions if action == "acceleration" else env.hover_actions
    env.step(actions())  # warm
    steps, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        env.step(actions())
        steps += 1
    wall = time.perf_counter() - start
    return steps / wall, steps * action_steps * 1e-3 / wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0, help="wall time per figure")
    args = parser.parse_args()
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    for followers in (7, 49):
        for action_steps in (50, 1):
            rate, real = measure(followers, action_steps, args.seconds)
            print(f"{followers:3d} followers, {action_steps:2d} physics steps per env step: "
                  f"{rate:8.1f} env steps/s ({real:.2f}x real time)")
    for followers in (7, 49):
        rate, real = measure(followers, 1, args.seconds, action="thrust_moment")
        print(f"{followers:3d} followers, thrust and moments, 1 physics step per env step: "
              f"{rate:8.1f} env steps/s ({real:.2f}x real time)")
    print(f"load average after:  {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()

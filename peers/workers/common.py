# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""What every peer worker shares: the task protocol, the timed workload loop, the dynamics tiers.

A worker runs in its peer's own virtual environment: `python worker_X.py TASK.json RESULT.json`.
A backend gives: `physics_hz`, `control_hz`, `hosts_law`, `make(starts)`, `command(pos, vel,
acc)` (references to the peer's own position controller, (n, 3) each), `advance()` (physics for
one control period), `positions()`, `velocities()` ((n, 3)), and for the dynamics tiers
`accel(state, thrusts)`, `open_loop(state, schedule, hz)`, `rotor_step(...)`."""

import json
import math
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

import numpy as np  # noqa: E402

from peerlib import params as P  # noqa: E402
from peerlib import workload as W  # noqa: E402
from peerlib.scenarios import open_loop_schedule, tier_states  # noqa: E402,F401


def fly(backend_cls, workload, n, controller, duration, wall_budget, warmup_periods=1):
    """One timed run. Returns dict with the stepping wall time, simulated time, errors. The first
    `warmup_periods` control periods (JIT compilation) are timed apart from the stepping."""
    t_setup = time.perf_counter()
    sim = backend_cls()
    starts = W.hover_points(n) if workload == "W1" else W.starts(n)
    sim.make(starts)
    setup = time.perf_counter() - t_setup
    period = 1.0 / sim.control_hz
    steps_per_ctrl = sim.physics_hz / sim.control_hz
    smc = W.DiscreteSmc(n - 1) if (workload == "W2" and controller == "smc" and n > 1) else None
    u_hold = np.zeros((max(n - 1, 0), 2))
    next_sample = 0.0
    errors = []
    k, t = 0, 0.0
    n_ctrl = int(round(duration * sim.control_hz))
    warm = None
    t0 = time.perf_counter()
    while k < n_ctrl:
        t = k * period
        if workload == "W1":
            pos = W.hover_points(n)
            sim.command(pos, np.zeros((n, 3)), np.zeros((n, 3)))
        else:
            p0, v0, a0 = W.leader(t)
            ps, vs, as_ = W.slot_references(t, n - 1)
            pos, vel, acc = np.vstack([p0, ps]), np.vstack([v0, vs]), np.vstack([a0, as_])
            if smc is not None:
                if t + 1e-9 >= next_sample:   # zero-order hold of eq. (48) at T
                    x, v = sim.positions(), sim.velocities()
                    leader_pv = np.r_[x[0, :2], v[0, :2]]
                    u_hold = W.limit_tilt(smc(t, leader_pv, np.hstack([x[1:, :2], v[1:, :2]])))
                    next_sample += W.SMC["period"]
                x, v = sim.positions(), sim.velocities()
                pos[1:, :2], vel[1:, :2] = x[1:, :2], v[1:, :2]
                acc[1:, :2] = u_hold
                vel[1:, 2] = 0.0
            sim.command(pos, vel, acc)
        sim.advance()
        k += 1
        if k == warmup_periods:
            warm = time.perf_counter() - t0   # first control periods: JIT / first-call costs
            t0 = time.perf_counter()
        t = k * period
        if k % max(1, int(round(0.1 * sim.control_hz))) == 0 and 25.0 <= t <= 40.0 + 1e-9:
            x = sim.positions()
            errors.append(W.hover_error(x, n) if workload == "W1" else W.slot_error(t, x, n - 1))
        if time.perf_counter() - t0 > wall_budget:
            break
    wall = time.perf_counter() - t0
    x = sim.positions()
    final = W.hover_error(x, n) if workload == "W1" else (W.slot_error(t, x, n - 1) if n > 1 else 0.0)
    sim.close()
    sim_time = (k - warmup_periods) * period
    return {"setup_s": setup, "warmup_s": warm, "wall_s": wall, "sim_s": sim_time,
            "physics_steps": int(round((k - warmup_periods) * steps_per_ctrl)),
            "error_mean_25_40": (sum(errors) / len(errors)) if errors else None,
            "error_final": final, "finite": bool(np.all(np.isfinite(x)))}


def speed(backend_cls, job):
    runs = []
    for _ in range(job["repeats"]):
        runs.append(fly(backend_cls, job["workload"], job["n"], job["controller"], job["duration"],
                        job["wall_budget"], job.get("warmup_periods", 1)))
    return {"runs": runs, "physics_hz": backend_cls.physics_hz, "control_hz": backend_cls.control_hz}


# ---- dynamics tiers -----------------------------------------------------------------------------
def dynamics(backend_cls, bare=False):
    """Tiers (a)-(c). bare: the peer's unmatched terms (drag, propeller inertia) switched off."""
    make = (lambda: backend_cls(bare=True)) if bare else backend_cls
    out = {"accel": {}, "open_loop": None, "rotor_step": None, "bare": bare}
    for name, st in tier_states().items():
        sim = make()
        out["accel"][name] = sim.accel(st)
        sim.close()
    sim = make()
    hz = 20.0
    out["open_loop"] = sim.open_loop({"pos": [0, 0, 20.0], "quat": [0, 0, 0, 1], "vel": [0, 0, 0],
                                      "omega": [0, 0, 0]}, open_loop_schedule(hz), hz)
    sim.close()
    sim = make()
    h = P.derived()["hover_thrust"]
    out["rotor_step"] = sim.rotor_step(h, 1.3 * h, 0.4)
    sim.close()
    return out


def main(backend_cls):
    task = json.load(open(sys.argv[1]))
    result = {"peer": task["peer"], "jobs": []}
    for job in task["jobs"]:
        entry = {"job": job}
        t0 = time.perf_counter()
        try:
            if job["kind"] == "speed":
                entry.update(speed(backend_cls, job))
            elif job["kind"] == "dynamics":
                entry.update(dynamics(backend_cls, job.get("bare", False)))
        except Exception as exc:  # recorded, reported in PEERS.md with its message
            import traceback
            entry["error"] = f"{type(exc).__name__}: {exc}"
            entry["traceback"] = traceback.format_exc()[-2000:]
        entry["elapsed_s"] = time.perf_counter() - t0
        result["jobs"].append(entry)
        json.dump(result, open(sys.argv[2], "w"), indent=1, default=float)
    json.dump(result, open(sys.argv[2], "w"), indent=1, default=float)


def median(values):
    return statistics.median(values) if values else float("nan")

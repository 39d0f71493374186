# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Crazyflow 0.4 (+ drone-models 0.1) driven as its examples drive it: one Sim holding N drones in
one world (n_worlds = 1; a batch of worlds is timed apart), first_principles dynamics at its
default 500 Hz, Euler, the Mellinger state controller at 100 Hz (state_control every 5 steps),
JAX on the CPU, single-threaded XLA. Drone cf2x_L250 with the reference's mass, inertia, arm,
thrust and torque curves, mixing and a symmetric first-order rotor lag set in sim.data.params;
the controllers' vehicle entries (thrust_max, L, rpm2thrust, thrust2torque, mixing) likewise;
their gains and the state controller's own mass stay Crazyflow's."""

import numpy as np
from common import P, main

import jax
import jax.numpy as jnp
from crazyflow.control import Control
from crazyflow.drones import Drone
from crazyflow.dynamics import Dynamics
from crazyflow.sim import Sim

RPM = P.RPM_PER_RAD_S


def matched(sim, bare=False):
    ref = P.crazyflow_params()
    d = P.derived()
    p = sim.data.params
    j = np.array(ref["J"])
    p = p.replace(mass=jnp.asarray(ref["mass"]), J=jnp.asarray(j), J_inv=jnp.asarray(np.linalg.inv(j)),
                  L=jnp.asarray(ref["L"]), rpm2thrust=jnp.asarray(ref["rpm2thrust"]),
                  rpm2torque=jnp.asarray(ref["rpm2torque"]), rotor_dyn_coef=jnp.asarray(ref["rotor_dyn_coef"]),
                  mixing_matrix=jnp.asarray(ref["mixing_matrix"]))
    if bare:   # its linear drag and propeller inertia off
        p = p.replace(drag_matrix=jnp.zeros_like(p.drag_matrix), prop_inertia=jnp.zeros_like(p.prop_inertia))
    vehicle = {"thrust_max": d["thrust_max"], "L": ref["L"][0], "rpm2thrust": ref["rpm2thrust"][0],
               "thrust2torque": d["yaw_arm"], "mixing_matrix": ref["mixing_matrix"], "thrust_min": 0.0}
    ctrls = sim.data.controls
    for name in ("state", "attitude", "force_torque"):
        c = getattr(ctrls, name)
        if c is None:
            continue
        new = dict(c.params)
        for k, v in vehicle.items():
            if k in new and not (name == "state" and k == "thrust_max"):
                new[k] = jnp.asarray(v, dtype=jnp.asarray(new[k]).dtype)
        ctrls = ctrls.replace(**{name: c.replace(params=new)})
    sim.data = sim.data.replace(params=p, controls=ctrls)


class Crazyflow:
    physics_hz = 500.0
    control_hz = 100.0
    hosts_law = True

    def __init__(self, bare=False):
        self.sim = None
        self.bare = bare

    def _make(self, n, control):
        kw = {"state_freq": 100} if control == Control.state else {}
        sim = Sim(n_worlds=1, n_drones=n, drone=Drone.cf2x_L250, dynamics=Dynamics.first_principles,
                  control=control, freq=500, **kw)
        matched(sim, self.bare)
        return sim

    def _set_state(self, sim, pos, quat=None, vel=None, omega=None, rotor_rpm=None):
        n = len(pos)
        st = sim.data.states
        rpm = P.derived()["hover_omega"] * RPM if rotor_rpm is None else rotor_rpm
        st = st.replace(pos=jnp.asarray(np.asarray(pos, float)[None], dtype=st.pos.dtype),
                        quat=jnp.asarray(np.tile(quat if quat is not None else [0, 0, 0, 1.0], (1, n, 1)), dtype=st.quat.dtype),
                        vel=jnp.asarray(np.tile(vel if vel is not None else [0, 0, 0.0], (1, n, 1)), dtype=st.vel.dtype),
                        ang_vel=jnp.asarray(np.tile(omega if omega is not None else [0, 0, 0.0], (1, n, 1)), dtype=st.ang_vel.dtype),
                        rotor_vel=jnp.asarray(np.broadcast_to(np.asarray(rpm, float), (1, n, 4)), dtype=st.rotor_vel.dtype))
        sim.data = sim.data.replace(states=st)

    def make(self, starts):
        self.sim = self._make(len(starts), Control.state)
        self._set_state(self.sim, starts)
        self.n = len(starts)
        self.steps = int(round(self.physics_hz / self.control_hz))

    def command(self, pos, vel, acc):
        cmd = np.zeros((1, self.n, 16))
        cmd[0, :, 0:3], cmd[0, :, 3:6], cmd[0, :, 6:9] = pos, vel, acc
        cmd[0, :, 12] = 1.0   # setpoint quaternion (x, y, z, w): yaw 0
        self.sim.state_control(cmd)

    def advance(self):
        self.sim.step(self.steps)

    def positions(self):
        return np.asarray(self.sim.data.states.pos[0])

    def velocities(self):
        return np.asarray(self.sim.data.states.vel[0])

    def close(self):
        if self.sim is not None:
            self.sim.close()
            self.sim = None

    # dynamics tiers ------------------------------------------------------------------------------
    def accel(self, st):
        """Crazyflow's own derivative (the function its integrator calls), at the matched params."""
        from crazyflow.sim.dynamics import first_principles_dynamics
        sim = self._make(1, Control.rotor_vel)
        rpm = [P.thrust_to_rpm(t) for t in st["thrusts"]]
        cmd = np.zeros(4)
        for i, j in enumerate(P.crazyflow_order()):
            cmd[j] = rpm[i]
        self._set_state(sim, [st["pos"]], st["quat"], st["vel"], st["omega"], rotor_rpm=cmd)
        sim.rotor_vel_control(jnp.asarray(cmd[None, None, :]))
        deriv = first_principles_dynamics(sim.data)
        self.sim = sim
        return {"lin": np.asarray(deriv.acc[0, 0]).tolist(), "ang": np.asarray(deriv.ang_acc[0, 0]).tolist()}

    def _rpm(self, thrusts):
        cmd = np.zeros(4)
        for i, j in enumerate(P.crazyflow_order()):
            cmd[j] = P.thrust_to_rpm(thrusts[i])
        return cmd

    def open_loop(self, st, schedule, hz):
        sim = self._make(1, Control.rotor_vel)
        self._set_state(sim, [st["pos"]])
        steps = int(round(self.physics_hz / hz))
        ts, xs, k = [0.0], [list(st["pos"])], 0
        for row in schedule:
            sim.rotor_vel_control(jnp.asarray(self._rpm(row)[None, None, :]))
            for _ in range(steps):
                sim.step(1)
                k += 1
                ts.append(k / self.physics_hz)
                xs.append(np.asarray(sim.data.states.pos[0, 0]).tolist())
        self.sim = sim
        return {"t": ts, "pos": xs, "rate_hz": self.physics_hz}

    def rotor_step(self, t_from, t_to, duration):
        sim = self._make(1, Control.rotor_vel)
        self._set_state(sim, [[0, 0, 5.0]], rotor_rpm=self._rpm([t_from] * 4))
        sim.rotor_vel_control(jnp.asarray(self._rpm([t_to, t_from, t_from, t_from])[None, None, :]))
        j = P.crazyflow_order()[0]
        k2 = P.crazyflow_params()["rpm2thrust"][0][2]
        ts, th = [0.0], [t_from]
        for k in range(int(round(duration * self.physics_hz))):
            sim.step(1)
            ts.append((k + 1) / self.physics_hz)
            th.append(float(k2 * float(sim.data.states.rotor_vel[0, 0, j]) ** 2))
        self.sim = sim
        return {"t": ts, "thrust": th, "note": "thrust = rpm2thrust rpm^2 of the rotor state"}


def batch(job):
    """W2 at n = job["n"] in job["worlds"] worlds at once (Crazyflow's batching): every world flies
    the same references under the Mellinger state controller. Returns the stepping wall time."""
    import time
    from common import W
    n, worlds, duration = job["n"], job["worlds"], job["duration"]
    t0 = time.perf_counter()
    sim = Sim(n_worlds=worlds, n_drones=n, drone=Drone.cf2x_L250, dynamics=Dynamics.first_principles,
              control=Control.state, freq=500, state_freq=100)
    matched(sim)
    st = sim.data.states
    starts = np.broadcast_to(W.starts(n)[None], (worlds, n, 3))
    rpm = P.derived()["hover_omega"] * RPM
    sim.data = sim.data.replace(states=st.replace(
        pos=jnp.asarray(starts, dtype=st.pos.dtype),
        rotor_vel=jnp.full(st.rotor_vel.shape, rpm, dtype=st.rotor_vel.dtype)))
    setup = time.perf_counter() - t0
    steps, k_max = 5, int(round(duration * 100))
    warm, t0 = None, time.perf_counter()
    for k in range(k_max):
        t = k / 100.0
        p0, v0, a0 = W.leader(t)
        ps, vs, as_ = W.slot_references(t, n - 1)
        cmd = np.zeros((worlds, n, 16))
        cmd[:, :, 0:3] = np.vstack([p0, ps])
        cmd[:, :, 3:6] = np.vstack([v0, vs])
        cmd[:, :, 6:9] = np.vstack([a0, as_])
        cmd[:, :, 12] = 1.0
        sim.state_control(cmd)
        sim.step(steps)
        if k == 0:
            sim.data.states.pos.block_until_ready()
            warm, t0 = time.perf_counter() - t0, time.perf_counter()
    sim.data.states.pos.block_until_ready()
    wall = time.perf_counter() - t0
    pos = np.asarray(sim.data.states.pos)
    err = float(np.mean([W.slot_error((k_max - 1) / 100.0 + 0.01, pos[w], n - 1) for w in range(worlds)]))
    return {"worlds": worlds, "n": n, "setup_s": setup, "warmup_s": warm, "wall_s": wall,
            "sim_s": (k_max - 1) / 100.0, "runs_per_hour": worlds * 3600.0 / (wall + warm + setup),
            "runs_per_hour_stepping": worlds * 3600.0 / wall, "final_error": err,
            "xla_flags": __import__("os").environ.get("XLA_FLAGS")}


if __name__ == "__main__":
    import json
    import sys
    task = json.load(open(sys.argv[1]))
    if task["jobs"] and task["jobs"][0]["kind"] == "batch":
        out = {"peer": "crazyflow", "jobs": []}
        for job in task["jobs"]:
            try:
                out["jobs"].append(dict(batch(job), job=job))
            except Exception as exc:
                out["jobs"].append({"job": job, "error": f"{type(exc).__name__}: {exc}"})
            json.dump(out, open(sys.argv[2], "w"), indent=1, default=float)
    else:
        main(Crazyflow)

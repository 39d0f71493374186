# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""PyFlyt 0.29 driven as its users drive it: one Aviary (PyBullet, DIRECT, no render) with N
QuadX drones at its defaults (physics 240 Hz, control 120 Hz), flight mode 7 (x, y, yaw, z
setpoints into its cascaded PIDs). The drone is PyFlyt's cf2x structure at the reference's mass,
inertia, rotor positions and motor constants (URDF and YAML written to a temporary folder); its
drag and controller gains are read from the installed cf2x.yaml."""

import os
import tempfile

import numpy as np
import yaml
from common import P, main

import PyFlyt
from PyFlyt.core import Aviary

MODEL = "cfref"


def model_dir(bare=False):
    own = os.path.join(os.path.dirname(PyFlyt.__file__), "models", "vehicles", "cf2x", "cf2x.yaml")
    with open(own) as f:
        cf2x = yaml.safe_load(f)
    root = tempfile.mkdtemp(prefix="pyflyt_cfref_")
    os.makedirs(os.path.join(root, MODEL))
    with open(os.path.join(root, MODEL, MODEL + ".urdf"), "w") as f:
        f.write(P.pyflyt_urdf())
    drag = {k: 0.0 for k in cf2x["drag_params"]} if bare else cf2x["drag_params"]
    body = P.pyflyt_yaml(drag=drag,
                         controller_yaml=yaml.safe_dump({"control_params": cf2x["control_params"]}))
    with open(os.path.join(root, MODEL, MODEL + ".yaml"), "w") as f:
        f.write(body)
    return root


class PyFlyt_:
    physics_hz = 240.0
    control_hz = 120.0
    hosts_law = False   # mode 6 takes velocities, no mode takes accelerations: see PEERS.md

    def __init__(self, control_hz=120, bare=False):
        self.dir = model_dir(bare)   # bare: body and rotational drag off
        self.env = None
        self.ctrl_hz = control_hz

    def _aviary(self, starts, mode):
        opts = {"model_dir": self.dir, "drone_model": MODEL, "control_hz": self.ctrl_hz}
        env = Aviary(start_pos=np.asarray(starts, float), start_orn=np.zeros((len(starts), 3)),
                     drone_type="quadx", drone_options=opts, render=False, physics_hz=240, seed=1)
        env.set_mode(mode)
        return env

    def make(self, starts):
        self.env = self._aviary(starts, 7)
        self.n = len(starts)

    def command(self, pos, vel, acc):
        sp = np.stack([pos[:, 0], pos[:, 1], np.zeros(len(pos)), pos[:, 2]], axis=1)
        self.env.set_all_setpoints(sp)

    def advance(self):
        self.env.step()

    def positions(self):
        return np.array([d.state[3] for d in self.env.drones])

    def velocities(self):
        # state[2] is the body-frame linear velocity: rotate to the world frame
        out = []
        for d in self.env.drones:
            _, q = self.env.getBasePositionAndOrientation(d.Id)
            r = np.array(self.env.getMatrixFromQuaternion(q)).reshape(3, 3)
            out.append(r @ d.state[2])
        return np.array(out)

    def close(self):
        if self.env is not None:
            self.env.disconnect()
            self.env = None

    # dynamics tiers ------------------------------------------------------------------------------
    def _single(self, st, pwm):
        env = self._aviary([st["pos"]], -1)
        d = env.drones[0]
        env.resetBasePositionAndOrientation(d.Id, st["pos"], st["quat"])
        r = np.array(env.getMatrixFromQuaternion(st["quat"])).reshape(3, 3)
        env.resetBaseVelocity(d.Id, st["vel"], (r @ np.asarray(st["omega"], float)).tolist())
        d.update_state()
        d.motors.throttle = np.array(pwm, float)
        d.setpoint = np.array(pwm, float)
        d.pwm = np.array(pwm, float)
        self.env = env
        return env, d

    def accel(self, st):
        """PyBullet has no forward-dynamics query: one 1/240 s step from the state, acceleration
        = velocity change / dt (Bullet integrates semi-implicitly: v+ = v + a(x, v) dt)."""
        env, d = self._single(st, P.pyflyt_pwm(st["thrusts"]))
        v0, w0 = env.getBaseVelocity(d.Id)
        d.update_physics()
        env.stepSimulation()
        v1, w1 = env.getBaseVelocity(d.Id)
        _, q = env.getBasePositionAndOrientation(d.Id)
        r = np.array(env.getMatrixFromQuaternion(st["quat"])).reshape(3, 3)
        dt = 1.0 / 240.0
        lin = (np.array(v1) - np.array(v0)) / dt
        ang = r.T @ ((np.array(w1) - np.array(w0)) / dt)
        return {"lin": lin.tolist(), "ang": ang.tolist(), "note": "finite difference of one 1/240 s step"}

    def open_loop(self, st, schedule, hz):
        self.ctrl_hz = 240
        env, d = self._single(dict(st, thrusts=None), P.pyflyt_pwm([P.derived()["hover_thrust"]] * 4))
        steps = int(round(240 / hz))
        ts, xs = [0.0], [list(st["pos"])]
        k = 0
        for row in schedule:
            env.set_setpoint(0, np.array(P.pyflyt_pwm(row)))
            for _ in range(steps):
                env.step()
                k += 1
                ts.append(k / 240.0)
                xs.append([float(v) for v in d.state[3]])
        return {"t": ts, "pos": xs, "rate_hz": 240.0}

    def rotor_step(self, t_from, t_to, duration):
        self.ctrl_hz = 240
        h = P.pyflyt_pwm([t_from] * 4)
        env, d = self._single({"pos": [0, 0, 5.0], "quat": [0, 0, 0, 1], "vel": [0, 0, 0],
                               "omega": [0, 0, 0]}, h)
        cmd = P.pyflyt_pwm([t_to, t_from, t_from, t_from])
        j = P.pyflyt_order()[0]
        env.set_setpoint(0, np.array(cmd))
        t_max = P.derived()["thrust_max"]
        ts, th = [0.0], [t_from]
        for k in range(int(round(duration * 240))):
            env.step()
            ts.append((k + 1) / 240.0)
            th.append(float(t_max * d.motors.throttle[j] ** 2))
        return {"t": ts, "thrust": th, "note": "thrust = (total/4) throttle^2 of the motor state"}


if __name__ == "__main__":
    main(PyFlyt_)

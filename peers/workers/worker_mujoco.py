# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjformation's vehicle for the dynamics tiers: the MJCF that mjformation flies (the scene.xml a
one-vehicle run composed, when the task names one; else the generated reference MJCF), stepped by
MuJoCo from PyPI (mujoco==4.0.1, the engine mjformation is moving to) with mj_step and the model's
Euler integrator at 1 kHz, as the runner steps it. The workloads' speed is measured on the runner
itself (peers/run_peers.py), not here."""

import json
import sys

import mujoco
import numpy as np
from common import P

MODEL = None


class Mujoco:
    physics_hz = 1000.0

    def __init__(self):
        self.m = mujoco.MjModel.from_xml_path(MODEL) if MODEL.endswith(".xml") else mujoco.MjModel.from_xml_string(MODEL)
        self.d = mujoco.MjData(self.m)
        self.m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT   # open loop: no ground
        names = [mujoco.mj_id2name(self.m, mujoco.mjtObj.mjOBJ_ACTUATOR, i) for i in range(self.m.nu)]
        self.act = [names.index(n) if n in names else names.index("uav0_" + n) for n in self._rotor_names(names)]
        self.physics_hz = 1.0 / self.m.opt.timestep

    @staticmethod
    def _rotor_names(names):
        """The four rotors of vehicle 0 (the leader) in reference order r1..r4: in scene.xml the
        runner renames them to its contract's rotor0..rotor3 in the order `rotors` lists."""
        for cand in (list(P.MJCF_ROTORS), ["rotor0", "rotor1", "rotor2", "rotor3"]):
            found = [n for n in names for c in cand if n == c or n.endswith("_" + c) and n.startswith(("uav0_", "leader_", "v0_"))]
            if len(found) == 4:
                return found
        for cand in (list(P.MJCF_ROTORS), ["rotor0", "rotor1", "rotor2", "rotor3"]):
            found = [next((n for n in names if n.endswith(c)), None) for c in cand]
            if all(found):
                return found
        raise ValueError(f"no rotor actuators among {names}")

    def _set(self, st, thrusts):
        d = self.d
        mujoco.mj_resetData(self.m, d)
        q = st["quat"]
        d.qpos[0:3] = st["pos"]
        d.qpos[3:7] = [q[3], q[0], q[1], q[2]]
        d.qvel[0:3] = st["vel"]
        d.qvel[3:6] = st["omega"]   # free joint: angular velocity in the body frame
        for i, a in enumerate(self.act):
            d.ctrl[a] = thrusts[i]
            d.act[self.m.actuator_actadr[a]] = thrusts[i]

    def accel(self, st):
        self._set(st, st["thrusts"])
        mujoco.mj_forward(self.m, self.d)
        return {"lin": self.d.qacc[0:3].tolist(), "ang": self.d.qacc[3:6].tolist()}

    def open_loop(self, st, schedule, hz):
        h = P.derived()["hover_thrust"]
        self._set(st, [h] * 4)
        steps = int(round(self.physics_hz / hz))
        ts, xs = [0.0], [list(st["pos"])]
        for row in schedule:
            for i, a in enumerate(self.act):
                self.d.ctrl[a] = row[i]
            for _ in range(steps):
                mujoco.mj_step(self.m, self.d)
                ts.append(self.d.time)
                xs.append(self.d.qpos[0:3].tolist())
        return {"t": ts, "pos": xs, "rate_hz": self.physics_hz}

    def rotor_step(self, t_from, t_to, duration):
        st = {"pos": [0, 0, 5.0], "quat": [0, 0, 0, 1], "vel": [0, 0, 0], "omega": [0, 0, 0]}
        self._set(st, [t_from] * 4)
        self.d.ctrl[self.act[0]] = t_to
        a0 = self.m.actuator_actadr[self.act[0]]
        ts, th = [0.0], [t_from]
        for _ in range(int(round(duration * self.physics_hz))):
            mujoco.mj_step(self.m, self.d)
            ts.append(self.d.time)
            th.append(float(self.d.act[a0]))
        return {"t": ts, "thrust": th, "note": "thrust = the actuator's filter state (act)"}

    def close(self):
        pass


if __name__ == "__main__":
    import common
    task = json.load(open(sys.argv[1]))
    MODEL = task.get("model") or P.mjcf()
    result = {"peer": "mjformation", "model": task.get("model") or "generated reference MJCF",
              "mujoco": mujoco.__version__, "jobs": []}
    try:
        entry = {"job": {"kind": "dynamics"}}
        entry.update(common.dynamics(Mujoco))
    except Exception as exc:
        import traceback
        entry["error"] = f"{type(exc).__name__}: {exc}"
        entry["traceback"] = traceback.format_exc()[-2000:]
    result["jobs"].append(entry)
    json.dump(result, open(sys.argv[2], "w"), indent=1, default=float)

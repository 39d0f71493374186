# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""RotorPy 3.0 driven as its examples drive it: one Multirotor per vehicle (cmd_motor_speeds,
aero on), its SE3Control every step, vehicle.step over 1 / sim_rate (RotorPy's default 100 Hz,
scipy solve_ivp RK45 inside each step)."""

import numpy as np
from common import P, main

from rotorpy.controllers.quadrotor_control import SE3Control
from rotorpy.vehicles.crazyflie_params import quad_params as CF
from rotorpy.vehicles.multirotor import Multirotor


class RotorPy:
    physics_hz = 100.0
    control_hz = 100.0
    hosts_law = True

    def __init__(self, bare=False):
        self.aero = not bare   # bare: RotorPy's rotor drag (aero) off
        self.params = P.rotorpy_params(base=CF)
        self.params["rotor_pos"] = {k: np.array(v) for k, v in self.params["rotor_pos"].items()}
        self.params["rotor_directions"] = np.array(self.params["rotor_directions"])
        self.vehicles, self.ctrls, self.states, self.flat = [], [], [], []

    def _state(self, pos, quat=(0, 0, 0, 1), vel=(0, 0, 0), omega=(0, 0, 0), rotor=None):
        w = P.derived()["hover_omega"] if rotor is None else None
        return {"x": np.array(pos, float), "v": np.array(vel, float), "q": np.array(quat, float),
                "w": np.array(omega, float), "wind": np.zeros(3),
                "rotor_speeds": np.array(rotor if rotor is not None else [w] * 4, float)}

    def make(self, starts):
        for p in starts:
            s = self._state(p)
            self.vehicles.append(Multirotor(self.params, initial_state=s, control_abstraction="cmd_motor_speeds", aero=self.aero))
            self.ctrls.append(SE3Control(self.params))
            self.states.append(s)

    def command(self, pos, vel, acc):
        z = np.zeros(3)
        self.flat = [{"x": pos[i], "x_dot": vel[i], "x_ddot": acc[i], "x_dddot": z, "x_ddddot": z,
                      "yaw": 0.0, "yaw_dot": 0.0, "yaw_ddot": 0.0} for i in range(len(pos))]

    def advance(self):
        dt = 1.0 / self.physics_hz
        for i, (veh, ctrl) in enumerate(zip(self.vehicles, self.ctrls)):
            u = ctrl.update(0.0, self.states[i], self.flat[i])
            self.states[i] = veh.step(self.states[i], u, dt)

    def positions(self):
        return np.array([s["x"] for s in self.states])

    def velocities(self):
        return np.array([s["v"] for s in self.states])

    def close(self):
        pass

    # dynamics tiers
    def _vehicle(self, abstraction="cmd_motor_thrusts"):
        return Multirotor(self.params, control_abstraction=abstraction, aero=self.aero)

    def accel(self, st):
        omegas = [P.thrust_to_omega(t) for t in st["thrusts"]]
        s = self._state(st["pos"], st["quat"], st["vel"], st["omega"], rotor=omegas)
        d = self._vehicle().statedot(s, {"cmd_motor_thrusts": np.array(st["thrusts"])}, 0.001)
        return {"lin": list(map(float, d["vdot"])), "ang": list(map(float, d["wdot"]))}

    def open_loop(self, st, schedule, hz):
        veh = self._vehicle()
        s = self._state(st["pos"], st["quat"], st["vel"], st["omega"])
        steps = int(round(self.physics_hz / hz))
        t, ts, xs = 0.0, [0.0], [list(s["x"])]
        for row in schedule:
            for _ in range(steps):
                s = veh.step(s, {"cmd_motor_thrusts": np.array(row)}, 1.0 / self.physics_hz)
                t += 1.0 / self.physics_hz
                ts.append(t)
                xs.append(list(map(float, s["x"])))
        return {"t": ts, "pos": xs, "rate_hz": self.physics_hz}

    def rotor_step(self, t_from, t_to, duration):
        """The thrust of rotor r1 (k_eta w^2 of its state) after its command steps; sampled at
        1 kHz (the rotor ODE integrated by RotorPy's own step at dt = 1 ms)."""
        veh = self._vehicle()
        w0 = P.thrust_to_omega(t_from)
        s = self._state([0, 0, 0.5], rotor=[w0] * 4)
        cmd = np.array([t_to, t_from, t_from, t_from])
        ts, th = [0.0], [t_from]
        for k in range(int(round(duration * 1000))):
            s = veh.step(s, {"cmd_motor_thrusts": cmd}, 0.001)
            ts.append((k + 1) * 0.001)
            th.append(float(self.params["k_eta"] * s["rotor_speeds"][0] ** 2))
        return {"t": ts, "thrust": th, "note": "thrust = k_eta w^2 of the rotor-speed state"}


if __name__ == "__main__":
    main(RotorPy)

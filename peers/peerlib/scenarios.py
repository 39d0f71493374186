# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The dynamics tiers' inputs, the same for every simulator: the states and thrusts of tier (a)
and the open-loop thrust sequence of tier (b)."""

import math

import numpy as np

from . import params as P


def rot_xyzw(roll, pitch, yaw):
    """Quaternion (x, y, z, w) of the ZYX Euler angles."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return np.array([sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                     cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy])


def tier_states():
    """The states of tier (a): pos, quat xyzw, world velocity, body angular velocity, thrusts (N,
    reference rotor order r1..r4)."""
    h = P.derived()["hover_thrust"]
    thr = [h * 1.05, h * 0.95, h * 1.02, h * 0.98]
    return {
        "level_at_rest": {"pos": [0, 0, 0.5], "quat": rot_xyzw(0, 0, 0).tolist(), "vel": [0, 0, 0],
                          "omega": [0, 0, 0], "thrusts": thr},
        "tilted_moving": {"pos": [0, 0, 0.5], "quat": rot_xyzw(0.2, -0.1, 0.3).tolist(),
                          "vel": [1.0, -0.5, 0.3], "omega": [0.5, -0.4, 0.3], "thrusts": thr},
    }


def open_loop_schedule(hz=20.0, duration=4.0):
    """Per-rotor thrust commands (N, reference order) held for 1 / hz each: hover plus a small
    differential (0.1 %, 0.07 %) that rolls and pitches the vehicle back and forth (yaw-neutral pairs)."""
    h = P.derived()["hover_thrust"]
    rows = []
    for k in range(int(round(duration * hz))):
        t = k / hz
        a = 0.001 * h * math.sin(2 * math.pi * 0.5 * t)
        b = 0.0007 * h * math.sin(2 * math.pi * 0.3 * t + 1.0)
        # r1 (+,+), r2 (+,-), r3 (-,-), r4 (-,+): a rolls (y+ vs y-), b pitches (x+ vs x-)
        rows.append([h + a - b, h - a - b, h - a + b, h + a + b])
    return rows

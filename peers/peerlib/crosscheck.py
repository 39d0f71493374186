# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The dynamics tiers' arithmetic: divergence times, motor-lag times, and the accelerations each
peer's documented extra terms predict (so a difference is explained, not only listed)."""

import math

import numpy as np

from . import params as P


def on_grid(t, pos, grid):
    t, pos = np.asarray(t, float), np.asarray(pos, float)
    return np.stack([np.interp(grid, t, pos[:, k]) for k in range(3)], axis=1)


def separation(a, b, dt=0.001):
    """|p_a(t) - p_b(t)| on a common 1 ms grid (linear interpolation of each run's samples)."""
    end = min(a["t"][-1], b["t"][-1])
    grid = np.arange(0.0, end + 1e-12, dt)
    return grid, np.linalg.norm(on_grid(a["t"], a["pos"], grid) - on_grid(b["t"], b["pos"], grid), axis=1)


def divergence_time(a, b, threshold=0.05):
    """First time (s) the two open-loop runs are more than `threshold` m apart; None if never."""
    grid, sep = separation(a, b)
    over = np.nonzero(sep > threshold)[0]
    return float(grid[over[0]]) if len(over) else None


def lag_time(t, thrust, fraction=1.0 - math.exp(-1.0)):
    """Time (s) for the thrust to cover `fraction` of its step (63.2 % by default); linear
    interpolation between samples."""
    t, th = np.asarray(t, float), np.asarray(thrust, float)
    start, end = th[0], th[-1]
    target = start + fraction * (end - start)
    k = int(np.argmax(th >= target)) if end > start else int(np.argmax(th <= target))
    if k == 0:
        return float("nan")
    return float(t[k - 1] + (target - th[k - 1]) * (t[k] - t[k - 1]) / (th[k] - th[k - 1]))


def lag_on_speed(tau, ratio, final, fraction=1.0 - math.exp(-1.0)):
    """63.2 % time of the thrust when the first-order lag acts on rotor speed (thrust ~ w^2),
    for a thrust step of `ratio` (t_to / t_from) seen against the thrust `final` reached at the
    end of the record: w(t) = w0 (1 + r x), x = 1 - exp(-t / tau), r = sqrt(ratio) - 1."""
    r = math.sqrt(ratio) - 1.0
    lhs = 1.0 + fraction * (final - 1.0)        # thrust / t_from at the 63.2 % point
    x = (math.sqrt(lhs) - 1.0) / r
    return -tau * math.log(1.0 - x)


def lag_discrete(tau, dt, fraction=1.0 - math.exp(-1.0)):
    """63.2 % time of an explicit-Euler first-order lag y += dt / tau (u - y) stepped at dt."""
    return dt * math.log(1.0 - fraction) / math.log(1.0 - dt / tau)


def _rot(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def predicted_extra(peer, st, ref=P.REFERENCE):
    """Linear (world) and angular (body) acceleration the peer's unmatched terms add at state
    `st`, from their published formulas and coefficients (params.unmatched())."""
    m = ref["mass"]
    J = np.diag([ref["ixx"], ref["iyy"], ref["izz"]])
    R = _rot(st["quat"])
    v_b = R.T @ np.asarray(st["vel"], float)
    w = np.asarray(st["omega"], float)
    omega = np.array([P.thrust_to_omega(t) for t in st["thrusts"]])
    if peer == "rotorpy":   # rotor drag H_i = -w_i diag(k_d, k_d, k_z) (v_b + w x r_i) at each hub
        K = np.diag([1.0250600e-06, 1.0250600e-06, 7.553e-07])
        F, M = np.zeros(3), np.zeros(3)
        for r, wi in zip(P.rotor_positions(ref), omega):
            H = -wi * K @ (v_b + np.cross(w, r))
            F += H
            M += np.cross(r, H)
        return R @ F / m, np.linalg.solve(J, M)
    if peer == "pyflyt":    # body drag -sign(v) 0.5 rho Cd A v^2 per body axis; -sign(w) c w^2
        F = -np.sign(v_b) * 0.5 * 1.225 * 3.0 * 4.0e-4 * v_b ** 2
        M = -np.sign(w) * 1.0e-4 * w ** 2
        return R @ F / m, np.linalg.solve(J, M)
    if peer == "crazyflow":  # linear drag R D R^T v; propeller gyroscopic torque (w_y h, -w_x h, 0)
        D = np.diag([-0.014953790232821078, -0.014953790232821078, -0.013900090000325344])
        F = R @ D @ v_b
        spin = np.array(P.SIGNS, float)
        h = 34.52e-9 * float(np.sum(spin * omega))
        M = np.array([w[1] * h, -w[0] * h, 0.0])
        return F / m, np.linalg.solve(J, M)
    return np.zeros(3), np.zeros(3)

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The two workloads, in numpy, the same for every simulator (docs/PEERS.md).

W1: N vehicles hover at fixed points 0.5 m up, 0.3 m apart, for 40 s.
W2: Exp 2 at one tenth of its size (examples/vehicles/midge/exp2_midge.toml): the leader flies a 2
m circle at 0.157 rad/s, 0.5 m up; N - 1 followers keep slots on a 1 m circle turning at 0.314
rad/s around it (a hexagon for 6; for more followers the circle widens so neighbouring slots stay
>= 0.2 m apart, turning slower so that the slots keep their speed of 0.314 m/s about the leader,
and the followers start 0.85 m inside it, as the scaled Exp 2 starts them: a widened circle turning
at 0.314 rad/s asked 10 m/s and 3.1 m/s^2 of centripetal acceleration at N = 1000, and a start ring
at half its radius 16 m of reaching, which a tilt-limited quadrotor under (48) cannot fly: the slot
error grew). Followers fly either to their slot under the simulator's own position controller, or
under the discrete sliding-mode law, eq. (48) of Wang et al. 2021, ported here from
plugins/formation/src/discrete_smc.cc with the scaled Exp 2 gains."""

import math

import numpy as np

ALTITUDE = 0.5
LEADER_RADIUS, LEADER_OMEGA = 2.0, 0.157
SHAPE_OMEGA = 0.314
SMC = {"k1": 3.0, "k2": 1.0, "period": 0.05, "eps": 0.005, "q": 4.5, "u_min": -0.1, "u_max": 0.1,
       "boundary_layer": 0.01}
TILT_MAX = 0.78  # rad, the `geometric` attitude plugin's default tilt limit in mjformation


def limit_tilt(u):
    """Scale each (2,) horizontal acceleration to at most g tan(TILT_MAX), as mjformation's
    attitude plugin caps the tilt it asks for (the law's first samples ask for tens of m/s^2)."""
    cap = 9.81 * math.tan(TILT_MAX)
    norm = np.linalg.norm(u, axis=1, keepdims=True)
    return u * np.minimum(1.0, cap / np.maximum(norm, 1e-12))


def shape_radius(n_followers):
    return max(1.0, 0.2 * n_followers / (2.0 * math.pi))


def shape_omega(n_followers):
    """The circle's rate: 0.314 rad/s on the 1 m circle, slower on a widened one so that the slots
    move at the scaled Exp 2's 0.314 m/s about the leader at every N."""
    return SHAPE_OMEGA / shape_radius(n_followers)


def hover_points(n):
    """W1: n points on a square grid, 0.3 m apart, centred on the origin."""
    side = int(math.ceil(math.sqrt(n)))
    pts = [((k % side - (side - 1) / 2) * 0.3, (k // side - (side - 1) / 2) * 0.3, ALTITUDE)
           for k in range(n)]
    return np.array(pts)


def leader(t):
    """Leader position, velocity, acceleration (3,) each at time t (s)."""
    c, s = math.cos(LEADER_OMEGA * t), math.sin(LEADER_OMEGA * t)
    r, w = LEADER_RADIUS, LEADER_OMEGA
    return (np.array([r * c, r * s, ALTITUDE]), np.array([-r * w * s, r * w * c, 0.0]),
            np.array([-r * w * w * c, -r * w * w * s, 0.0]))


def shape(t, n_followers):
    """f_i(t) of Definition 1: (n, 6) rows px, py, vx, vy, ax, ay of each slot around the leader."""
    r, w = shape_radius(n_followers), shape_omega(n_followers)
    phase = w * t + 2.0 * math.pi * np.arange(n_followers) / n_followers
    c, s = np.cos(phase), np.sin(phase)
    return np.stack([r * c, r * s, -r * w * s, r * w * c, -r * w * w * c, -r * w * w * s], axis=1)


def starts(n):
    """Start positions (n, 3): the leader on its circle, followers on a ring 0.85 m inside the slot
    circle around the origin (0.15 m for up to 31 followers, as exp2_midge's follower_start), so
    that the reaching distance does not grow with N."""
    out = [np.array([LEADER_RADIUS, 0.0, ALTITUDE])]
    m = n - 1
    ring = 0.15 + (shape_radius(m) - 1.0)
    for i in range(m):
        a = 2.0 * math.pi * i / max(m, 1)
        out.append(np.array([ring * math.cos(a), ring * math.sin(a), ALTITUDE]))
    return np.array(out)


def slot_references(t, n_followers):
    """Each follower's slot: position, velocity, acceleration (n, 3) each (leader + f_i)."""
    p0, v0, a0 = leader(t)
    f = shape(t, n_followers)
    z = np.zeros(n_followers)
    p = np.stack([p0[0] + f[:, 0], p0[1] + f[:, 1], np.full(n_followers, ALTITUDE)], axis=1)
    v = np.stack([v0[0] + f[:, 2], v0[1] + f[:, 3], z], axis=1)
    a = np.stack([a0[0] + f[:, 4], a0[1] + f[:, 5], z], axis=1)
    return p, v, a


def ring_graph(n_followers):
    """exp2's topology for 6 followers and the runner's `generate = "ring"` in general: the leader
    talks to follower 1; followers form a bidirectional ring. Returns (a0 (n,), A (n, n))."""
    a0 = np.zeros(n_followers)
    a0[0] = 1.0
    adj = np.zeros((n_followers, n_followers))
    if n_followers > 1:
        for i in range(n_followers):
            for j in ((i + 1) % n_followers, (i - 1) % n_followers):
                if j != i:
                    adj[i, j] = 1.0
    return a0, adj


class DiscreteSmc:
    """Eq. (48) solved for the followers' accelerations as in discrete_smc.cc (eq. (53)
    rearranged): U = -Y / KB + L_H^-1 [H U0~ - ((qT - 1) S + eps T sat(S)) / KB]."""

    def __init__(self, n_followers, gains=SMC):
        self.g = dict(gains)
        self.n = n_followers
        a0, adj = ring_graph(n_followers)
        self.a0, self.adj = a0, adj
        self.lh = np.diag(adj.sum(axis=1)) - adj + np.diag(a0)  # L_H = L + diag(a_i0)
        self.lh_inv = np.linalg.inv(self.lh)

    def __call__(self, t, leader_pv, follower_pv):
        """leader_pv (4,) px py vx vy; follower_pv (n, 4). Returns u (n, 2), m/s^2."""
        g, n = self.g, self.n
        k1, k2, T = g["k1"], g["k2"], g["period"]
        kb = k2 * T
        mu1, mu2 = 0.5 * (g["u_max"] + g["u_min"]), 0.5 * (g["u_max"] - g["u_min"])  # eq. (48)
        f_now, f_next = shape(t, n), shape(t + T, n)
        z = follower_pv - f_now[:, :4] - leader_pv[None, :]
        err = self.a0[:, None] * z + (self.adj.sum(axis=1)[:, None] * z - self.adj @ z)  # eq. (16)
        s = k1 * err[:, :2] + k2 * err[:, 2:]                                        # eq. (17)
        sign = np.clip(s / g["boundary_layer"], -1.0, 1.0)
        rhs = self.a0[:, None] * (mu1 - mu2 * sign) - ((g["q"] * T - 1.0) * s + g["eps"] * T * sign) / kb
        rhs = self.lh_inv @ rhs
        p = follower_pv[:, :2] - leader_pv[None, :2]
        v = follower_pv[:, 2:] - leader_pv[None, 2:]
        y = k1 * (p + T * v) + k2 * v - k1 * f_next[:, :2] - k2 * f_next[:, 2:4]     # eq. (53)
        return -y / kb + rhs


def slot_error(t, positions, n_followers):
    """Mean horizontal distance (m) of the followers from their slots; positions (n+1, 3)."""
    p, _, _ = slot_references(t, n_followers)
    return float(np.mean(np.linalg.norm(positions[1:, :2] - p[:, :2], axis=1)))


def hover_error(positions, n):
    return float(np.mean(np.linalg.norm(positions - hover_points(n), axis=1)))

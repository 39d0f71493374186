# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Metrics recomputed from timeseries.csv, to cross-check the runner's summary.json.

sigma_f(t), eq. (68) of the paper: || X(t) - F(t) - 1_N (x) x_0(t) || over the positions and
velocities, both horizontal axes, of all followers. The CSV holds the slot
slot_i = p_0 + f_ip (leader's measured position + formation offset), so f_ip = slot_i - p_0.
The velocity offset f_iv is not in the CSV: for the paper's circle shape (f_ip rotating at
omega) f_iv = omega * (-f_ipy, f_ipx) exactly; otherwise it is the numerical time derivative
of f_ip.
"""

from __future__ import annotations

import math
import re

import numpy as np

# Table 1 of the paper: mean of sigma_f over t in [25, 40] s (Gazebo).
PAPER_SIGMA_F = {1: 0.8397, 2: 1.4405, 3: 4.5250}
PAPER_PROTOCOL = {
    1: "continuous, rho = 0.05",
    2: "discrete, T = 0.05 s, eps = 0.05, q = 4.5",
    3: "discrete, T = 0.2 s, eps = 0.05, q = 4.5",
}
# The paper's figure numbers per experiment: trajectories, final positions, pitch/roll, yaw,
# sliding variable s_1, sigma_f.
PAPER_FIGURES = {1: (10, 11, 12, 13, 14, 15), 2: (16, 17, 18, 19, 20, 21), 3: (22, 23, 24, 25, 26, 27)}
DEFAULT_WINDOW = (25.0, 40.0)
WINDOW_TOL = 1e-9  # as the runner's online metric: t in [t0 - 1e-9, t1 + 1e-9]


def vehicle_ids(ts: dict) -> list[int]:
    """Vehicle numbers present in the CSV (0 = leader, 1..N followers)."""
    ids = set()
    for name in ts:
        m = re.fullmatch(r"uav(\d+)_px", name)
        if m:
            ids.add(int(m.group(1)))
    return sorted(ids)


def followers(ts: dict) -> list[int]:
    return [i for i in vehicle_ids(ts) if i != 0]


def formation_deviation(ts: dict, omega: float | None = None) -> np.ndarray:
    """Per follower deviation x_i - f_i - x_0, array (rows, N, 4): px, py, vx, vy."""
    t = ts["t"]
    fs = followers(ts)
    out = np.empty((len(t), len(fs), 4))
    p0x, p0y, v0x, v0y = (ts[f"uav0_{c}"] for c in ("px", "py", "vx", "vy"))
    for k, i in enumerate(fs):
        fpx = ts[f"uav{i}_slot_x"] - p0x
        fpy = ts[f"uav{i}_slot_y"] - p0y
        if omega is not None and math.isfinite(omega):
            fvx, fvy = -omega * fpy, omega * fpx
        elif len(t) >= 2:
            fvx, fvy = np.gradient(fpx, t), np.gradient(fpy, t)
        else:
            fvx = fvy = np.full_like(t, np.nan)
        out[:, k, 0] = ts[f"uav{i}_px"] - ts[f"uav{i}_slot_x"]
        out[:, k, 1] = ts[f"uav{i}_py"] - ts[f"uav{i}_slot_y"]
        out[:, k, 2] = ts[f"uav{i}_vx"] - fvx - v0x
        out[:, k, 3] = ts[f"uav{i}_vy"] - fvy - v0y
    return out


def sigma_f_recomputed(ts: dict, omega: float | None = None) -> np.ndarray:
    """sigma_f(t), eq. (68), from the recorded states and slots."""
    d = formation_deviation(ts, omega)
    return np.sqrt(np.sum(d.reshape(len(d), -1) ** 2, axis=1))


def window_mask(t: np.ndarray, window=DEFAULT_WINDOW) -> np.ndarray:
    return (t >= window[0] - WINDOW_TOL) & (t <= window[1] + WINDOW_TOL)


def window_mean(t: np.ndarray, y: np.ndarray, window=DEFAULT_WINDOW) -> float:
    """Mean of the finite samples of y with t in the window (closed); NaN when there are none."""
    sel = y[window_mask(t, window)]
    sel = sel[np.isfinite(sel)]
    return float(sel.mean()) if sel.size else float("nan")


def final_slot_errors(ts: dict) -> np.ndarray:
    """Horizontal distance of each follower from its slot at the last recorded row."""
    return np.array([math.hypot(ts[f"uav{i}_px"][-1] - ts[f"uav{i}_slot_x"][-1],
                                ts[f"uav{i}_py"][-1] - ts[f"uav{i}_slot_y"][-1])
                     for i in followers(ts)])


def slot_radius(ts: dict, row: int = -1) -> float:
    """Formation radius from the slot columns: median distance slot - leader at `row`."""
    r = [math.hypot(ts[f"uav{i}_slot_x"][row] - ts["uav0_px"][row],
                    ts[f"uav{i}_slot_y"][row] - ts["uav0_py"][row]) for i in followers(ts)]
    r = [x for x in r if math.isfinite(x)]
    return float(np.median(r)) if r else float("nan")


def _number(x) -> float | None:
    if isinstance(x, bool):
        return None
    if isinstance(x, (int, float)):
        return float(x)
    if isinstance(x, str):
        try:
            return float(x)
        except ValueError:
            return None
    return None


def shape_parameters(summary: dict | None, config: dict | None) -> dict:
    """{'type', 'radius', 'omega'} of the formation shape, from summary.json `shape`, the
    formation plugin's attributes, or config.toml [formation.shape] (first found wins)."""
    out = {"type": None, "radius": None, "omega": None}
    sources = []
    if summary:
        sources.append(summary.get("shape") or {})
        sources.append(((summary.get("plugins") or {}).get("formation") or {}).get("attributes") or {})
    if config:
        sources.append((config.get("formation") or {}).get("shape") or {})
    for src in sources:
        if not isinstance(src, dict):
            continue
        if out["type"] is None and isinstance(src.get("type"), str):
            out["type"] = src["type"]
        for key in ("radius", "omega"):
            if out[key] is None:
                v = _number(src.get(key))
                if v is not None and math.isfinite(v):
                    out[key] = v
    return out


def circle_omega(summary: dict | None, config: dict | None) -> float | None:
    """omega of a circle shape (f_iv = omega J f_ip), None when the shape is not a circle."""
    p = shape_parameters(summary, config)
    if p["type"] in (None, "circle") and p["omega"] is not None:
        return p["omega"]
    return None


def paper_experiment(summary: dict | None, name: str) -> int | None:
    """The paper's experiment number (1, 2, 3) of a run, None when it is not one of them.

    summary.json `paper_experiment` decides when present (0 = not in the paper); otherwise the
    directory name's prefix exp1 / exp2 / exp3."""
    if summary and "paper_experiment" in summary:
        v = summary.get("paper_experiment")
        if isinstance(v, int) and not isinstance(v, bool):
            return v if v in PAPER_SIGMA_F else None
    m = re.match(r"exp([123])(?![0-9])", name)
    return int(m.group(1)) if m else None


def metric_window(summary: dict | None, config: dict | None = None) -> tuple[float, float]:
    w = ((summary or {}).get("metrics") or {}).get("sigma_f_window")
    if not (isinstance(w, list) and len(w) == 2):
        w = ((config or {}).get("run") or {}).get("metric_window")
    if isinstance(w, list) and len(w) == 2 and all(_number(x) is not None for x in w):
        return (float(w[0]), float(w[1]))
    return DEFAULT_WINDOW


def protocol_description(summary: dict | None, config: dict | None = None) -> str:
    """Short text of the formation protocol and its main parameters."""
    f = ((summary or {}).get("plugins") or {}).get("formation") or {}
    name = f.get("name")
    attrs = dict(f.get("attributes") or {})
    if not name and config:
        cf = config.get("formation") or {}
        name = cf.get("plugin")
        attrs = {k: v for k, v in cf.items() if not isinstance(v, dict)}
    if not name:
        return "?"
    keys = ("period", "rho", "eps", "q", "compensation", "reaching", "sign", "kp", "kv")
    if name == "smc_continuous" and str(attrs.get("reaching", "constant")) != "exponential":
        keys = tuple(k for k in keys if k != "q")
    parts = []
    for k in keys:
        if k in attrs:
            v = attrs[k]
            label = "T" if k == "period" else k
            unit = " s" if k == "period" else ""
            parts.append(f"{label} = {_fmt_attr(v)}{unit}")
    return f"{name} ({', '.join(parts)})" if parts else str(name)


def _fmt_attr(v) -> str:
    n = _number(v)
    if n is not None and not isinstance(v, str):
        return f"{n:g}"
    if isinstance(v, str) and n is not None:
        return f"{n:.6g}"  # the runner echoes attributes as full-precision text
    if isinstance(v, list):
        return "[" + ", ".join(_fmt_attr(x) for x in v) + "]"
    return str(v)

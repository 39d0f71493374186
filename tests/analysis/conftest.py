# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Fixtures: fake run directories that follow docs/ARCHITECTURE.md, with a known sigma_f."""

import json
import math
import struct
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest

ANALYSIS = Path(__file__).resolve().parents[2] / "analysis"
sys.path.insert(0, str(ANALYSIS))

N = 6
R_LEADER, W_LEADER = 20.0, 0.157
R, W = 10.0, 0.314
COLUMNS = ("px", "py", "pz", "vx", "vy", "vz", "roll", "pitch", "yaw", "ax_cmd", "ay_cmd",
           "sx", "sy", "slot_x", "slot_y")


def analytic_sigma(t, a, tau, c):
    """sigma_f(t) of the fixture: every follower is off its slot by (e(t), c) in position and
    (e'(t), 0) in velocity, e = a exp(-t / tau)."""
    e = a * np.exp(-t / tau)
    return np.sqrt(N * (e**2 + (e / tau) ** 2 + c**2))


def _tiny_png(path):
    """A 2x2 grey PNG (a stand-in for a rendered snapshot)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(
            ">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + b"\x80\x80\x80" * 2 for _ in range(2))
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    path.write_bytes(png)


CONFIG = """\
# Experiment file experiments/{name}.toml as run by mjformation.
[run]
name = "{name}"
paper_experiment = {exp}
duration = 40.0
metric_window = [25.0, 40.0]

[vehicles]
model = "{model}"
followers = 6

[topology]
leader_links = [1]
edges = [[1, 2], [2, 1], [2, 3], [3, 2], [3, 4], [4, 3], [4, 5], [5, 4], [5, 6], [6, 5], [6, 1], [1, 6]]

[formation]
plugin = "{plugin}"

[formation.shape]
type = "circle"
radius = 10.0
omega = 0.314
phase0 = 0.0
phase_step = 1.0471975511965976
"""


def make_run(root, name, *, exp=1, a=0.0, tau=5.0, c=0.1, complete=True, t_end=40.0,
             rate=20.0, sliding=True, snapshots=True, video=False, summary=True,
             model="quadrotor", plugin=None, delta=None, error_bound=None, network=None,
             events=None):
    """Writes a run directory root/name; returns (path, t, sigma_f(t))."""
    d = Path(root) / name
    (d / "snapshots").mkdir(parents=True)
    t = np.round(np.arange(0.0, t_end + 1e-9, 1.0 / rate), 9)
    e = a * np.exp(-t / tau)
    de = -e / tau
    p0 = np.stack([R_LEADER * np.cos(W_LEADER * t), R_LEADER * np.sin(W_LEADER * t)])
    v0 = np.stack([-R_LEADER * W_LEADER * np.sin(W_LEADER * t),
                   R_LEADER * W_LEADER * np.cos(W_LEADER * t)])
    sigma = analytic_sigma(t, a, tau, c)
    cols = {"t": t, "sigma_f": sigma}
    nan = np.full_like(t, np.nan)
    for i in range(N + 1):
        if i == 0:
            p, v, slot = p0, v0, p0
            s = (nan, nan)
        else:
            th = W * t + (i - 1) * math.pi / 3
            fp = np.stack([R * np.cos(th), R * np.sin(th)])
            fv = np.stack([-R * W * np.sin(th), R * W * np.cos(th)])
            slot = p0 + fp
            p = slot + np.stack([e, np.full_like(t, c)])
            v = v0 + fv + np.stack([de, np.zeros_like(t)])
            s = (3 * e + de, np.full_like(t, 3 * c)) if sliding else (nan, nan)
        vals = {"px": p[0], "py": p[1], "pz": np.full_like(t, 5.0), "vx": v[0], "vy": v[1],
                "vz": np.zeros_like(t), "roll": 0.05 * np.sin(0.5 * t + i),
                "pitch": -0.04 * np.cos(0.5 * t + i), "yaw": 0.01 * t,
                "ax_cmd": np.zeros_like(t), "ay_cmd": np.zeros_like(t),
                "sx": s[0], "sy": s[1], "slot_x": slot[0], "slot_y": slot[1]}
        for k in COLUMNS:
            cols[f"uav{i}_{k}"] = vals[k]
    names = list(cols)
    with open(d / "timeseries.csv", "w") as f:
        f.write(",".join(names) + "\n")
        data = np.stack([cols[n] for n in names], axis=1)
        for row in data:
            f.write(",".join("" if not math.isfinite(x) else f"{x:.9g}" for x in row) + "\n")
    plugin = plugin or {1: "smc_continuous", 2: "smc_discrete", 3: "smc_discrete"}.get(
        exp, "consensus_linear")
    (d / "config.toml").write_text(CONFIG.format(name=name, exp=exp, model=model, plugin=plugin))
    snaps = []
    if snapshots:
        for ts in (0.0, 10.0):
            rel = f"snapshots/t{ts:06.2f}.png"
            _tiny_png(d / rel)
            snaps.append(rel)
    if video:
        (d / "video.mp4").write_bytes(b"\x00\x00\x00\x18ftypmp42")
    win = (t >= 25.0 - 1e-9) & (t <= 40.0 + 1e-9)
    final_err = math.hypot(e[-1], c)
    if summary:
        attrs = {"k": "3 1", "eps": "0.05", "q": "4.5"}
        if plugin == "smc_discrete":
            attrs["period"] = "0.05" if exp == 2 else "0.2"
        report = {}
        if delta is not None:
            report["delta"] = delta
        if error_bound is not None:
            report["error_bound"] = error_bound
        s = {
            "experiment": name, "complete": complete,
            "error": None if complete else "non-finite state at t = %.2f s" % t_end,
            "paper_experiment": exp, "sim_time_s": float(t[-1]), "duration_s": 40.0,
            "seed": 1, "config_sha256": "0" * 64,
            "versions": {"mjformation": "0.1.0", "mujoco": "3.x"},
            "n_followers": N, "vehicle_model": model,
            "plugins": {"leader": {"name": "circle", "attributes": {}},
                        "formation": {"name": plugin, "attributes": attrs},
                        "attitude": {"name": "pd_cascade", "attributes": {}}},
            "shape": {"type": "circle", "radius": R, "omega": W},
            "metrics": {
                "sigma_f_window": [25.0, 40.0],
                "sigma_f_mean": float(sigma[win].mean()) if win.any() else None,
                "sigma_f_initial": float(sigma[0]), "sigma_f_final": float(sigma[-1]),
                "final_slot_error_m": [final_err] * N, "max_final_slot_error_m": final_err,
                "min_separation_m": 9.9, "reaching_time_s": 1.0,
                "max_abs_s_after_reaching": 0.01, "saturation_time_s": 0.0},
            "plugin_report": report, "snapshots": snaps,
        }
        if network is not None:
            s["network"] = network
        if events:  # [(kind, time_s, vehicles)]: summary.json "events" as the runner writes it
            by_kind = {}
            for kind, _, _ in events:
                by_kind[kind] = by_kind.get(kind, 0) + 1
            s["events"] = {"count": len(events), "by_kind": by_kind, "list": [
                {"kind": kind, "time_s": ts_, "vehicles": list(vs), "value": 95.0,
                 "what": f"follower {vs[0]} {kind} at {ts_:.2f} s (test)"}
                for kind, ts_, vs in events]}
        (d / "summary.json").write_text(json.dumps(s, indent=2))
    return d, t, sigma


@pytest.fixture
def fake_run(tmp_path):
    return make_run(tmp_path / "results", "exp2", exp=2, a=5.0, tau=4.0, c=0.2,
                    delta=0.2, error_bound=1.5)

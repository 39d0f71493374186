# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The peers harness's own logic, on mjformation alone (no peer installed): the parameter
matching, the numpy SMC law, the divergence and lag arithmetic, the table writer, and the
experiment files the runner accepts (when MJF_CLI names it)."""

import math
import os
import subprocess
import sys
from pathlib import Path
import xml.etree.ElementTree as ET

import numpy as np
import pytest

PEERS = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(PEERS))

from peerlib import crosscheck as X  # noqa: E402
from peerlib import experiments as E  # noqa: E402
from peerlib import params as P  # noqa: E402
from peerlib import tables as T  # noqa: E402
from peerlib import workload as W  # noqa: E402
from peerlib.scenarios import open_loop_schedule, tier_states  # noqa: E402


def wrench(positions, signs, thrusts):
    """Total thrust and body torques, computed from positions and spins independently of
    params.allocation: tau = sum r_i x (0, 0, T_i) + sign_i yaw_arm T_i z."""
    arm = P.derived()["yaw_arm"]
    tau = np.zeros(3)
    for r, s, t in zip(positions, signs, thrusts):
        tau += np.cross(r, [0.0, 0.0, t]) + np.array([0.0, 0.0, s * arm * t])
    return sum(thrusts), tau


# ---- parameter matching -------------------------------------------------------------------------
def test_reference_is_a_physical_rigid_body():
    r = P.REFERENCE
    assert r["ixx"] + r["iyy"] >= r["izz"] and r["iyy"] + r["izz"] >= r["ixx"]


def test_derived_values():
    d = P.derived()
    assert d["thrust_max"] == pytest.approx(2.3e-8 * 2500 ** 2)
    assert d["hover_thrust"] * 4 == pytest.approx(0.030 * 9.81)
    assert d["offset"] * math.sqrt(2) == pytest.approx(0.043)
    assert 1.9 < d["thrust_to_weight"] < 2.0


def test_mjcf_carries_the_reference():
    root = ET.fromstring(P.mjcf())
    inertial = root.find(".//body/inertial")
    assert float(inertial.get("mass")) == P.REFERENCE["mass"]
    assert [float(v) for v in inertial.get("diaginertia").split()] == [P.REFERENCE[k] for k in ("ixx", "iyy", "izz")]
    sites = {s.get("name"): [float(v) for v in s.get("pos").split()] for s in root.iter("site")}
    acts = list(root.iter("general"))
    assert [a.get("name") for a in acts] == list(P.MJCF_ROTORS)
    for a, (sx, sy), sign in zip(acts, P.QUADRANTS, P.SIGNS):
        x, y, _ = sites[a.get("site")]
        assert x * sx > 0 and y * sy > 0
        gear = [float(v) for v in a.get("gear").split()]
        assert gear[2] == 1.0 and gear[5] == pytest.approx(sign * P.derived()["yaw_arm"])
        assert float(a.get("dynprm")) == P.REFERENCE["tau_m"] and a.get("dyntype") == "filter"
        assert float(a.get("ctrlrange").split()[1]) == pytest.approx(P.derived()["thrust_max"])


def test_yaw_signs_give_no_yaw_at_equal_thrust_and_yaw_from_a_pair():
    total, tau = wrench(P.rotor_positions(), P.SIGNS, [0.07] * 4)
    assert total == pytest.approx(0.28) and np.allclose(tau, 0, atol=1e-15)
    _, tau = wrench(P.rotor_positions(), P.SIGNS, [0.08, 0.07, 0.08, 0.07])   # r1, r3 spin +1
    assert tau[2] > 0 and abs(tau[0]) < 1e-15 and abs(tau[1]) < 1e-15


def test_allocation_matches_the_wrench():
    thr = [0.071, 0.066, 0.08, 0.075]
    A = np.array(P.allocation(P.rotor_positions(), P.SIGNS, P.derived()["yaw_arm"]))
    total, tau = wrench(P.rotor_positions(), P.SIGNS, thr)
    assert np.allclose(A @ thr, [total, *tau])


def test_pyflyt_order_maps_place_and_spin():
    order = P.pyflyt_order()
    assert sorted(order) == [0, 1, 2, 3]
    pos = P.pyflyt_positions()
    for i, j in enumerate(order):
        assert np.sign(pos[j][0]) == P.QUADRANTS[i][0] and np.sign(pos[j][1]) == P.QUADRANTS[i][1]
        assert P.PYFLYT_YAW_SIGNS[j] == P.SIGNS[i]


def test_pyflyt_pwm_inverts_its_thrust_map():
    thr = [0.05, 0.07, 0.09, 0.11]
    pwm = P.pyflyt_pwm(thr)
    t_max = P.derived()["thrust_max"]
    for i, j in enumerate(P.pyflyt_order()):
        assert t_max * pwm[j] ** 2 == pytest.approx(thr[i])


def test_pyflyt_urdf_and_yaml():
    root = ET.fromstring(P.pyflyt_urdf().split("\n", 2)[2])
    links = {l.get("name"): l for l in root.iter("link")}
    assert float(links["base_link"].find("inertial/mass").get("value")) == P.REFERENCE["mass"]
    for k, p in enumerate(P.pyflyt_positions()):
        xyz = [float(v) for v in links[f"prop{k + 1}_link"].find("inertial/origin").get("xyz").split()]
        assert xyz == pytest.approx(list(p))
    y = P.pyflyt_yaml()
    assert f"tau: {P.REFERENCE['tau_m']!r}" in y and "noise_ratio: 0.0" in y


def test_crazyflow_mixing_reproduces_the_wrench():
    """Crazyflow: torque = L * mixing[0:2] @ F (roll, pitch), yaw = mixing[2] @ (c F)."""
    m = np.array(P.crazyflow_mixing())
    L = P.crazyflow_params()["L"][0]
    thr_ref = np.array([0.071, 0.066, 0.08, 0.075])
    order = P.crazyflow_order()
    f = np.zeros(4)
    for i, j in enumerate(order):
        f[j] = thr_ref[i]
    tau = np.array([L * m[0] @ f, L * m[1] @ f, P.derived()["yaw_arm"] * (m[2] @ f)])
    _, expect = wrench(P.rotor_positions(), P.SIGNS, thr_ref)
    assert np.allclose(tau, expect)


def test_crazyflow_rpm_map():
    k = P.crazyflow_params()["rpm2thrust"][0][2]
    rpm = P.thrust_to_rpm(0.07)
    assert k * rpm ** 2 == pytest.approx(0.07)
    assert P.crazyflow_params()["rotor_dyn_coef"][0] == [1 / 0.072, 0.0, 1 / 0.072, 0.0]


def test_rotorpy_params():
    p = P.rotorpy_params(base={"k_d": 1.0})
    assert p["k_d"] == 1.0 and p["tau_m"] == P.REFERENCE["tau_m"] and p["motor_noise_std"] == 0.0
    assert list(p["rotor_directions"]) == list(P.SIGNS)


def test_match_order_refuses_a_mirrored_layout():
    pos = P.rotor_positions()
    with pytest.raises(ValueError, match="r1"):
        P.match_order(pos, [-s for s in P.SIGNS])


# ---- workload and law ---------------------------------------------------------------------------
def test_smc_law_flies_a_double_integrator_to_its_slots():
    n = 6
    law = W.DiscreteSmc(n)
    x = W.starts(7)[1:, :2].copy()
    v = np.zeros((n, 2))
    u = np.zeros((n, 2))
    dt = 0.001
    for k in range(20000):
        t = k * dt
        if k % 50 == 0:
            p0, v0, _ = W.leader(t)
            u = W.limit_tilt(law(t, np.r_[p0[:2], v0[:2]], np.hstack([x, v])))
        v += u * dt
        x += v * dt
    pos = np.vstack([[0, 0, 0], np.c_[x, np.zeros(n)]])
    assert W.slot_error(20.0, pos, n) < 0.005


def test_limit_tilt_caps_the_norm():
    u = W.limit_tilt(np.array([[30.0, 40.0], [0.1, 0.0]]))
    assert np.linalg.norm(u[0]) == pytest.approx(9.81 * math.tan(W.TILT_MAX))
    assert u[1] == pytest.approx([0.1, 0.0])


def test_shape_is_consistent():
    """f_v = d f_p / dt and f_a = d f_v / dt (the runner's consistency check)."""
    h = 1e-6
    a, b = W.shape(3.0, 6), W.shape(3.0 + h, 6)
    assert np.allclose((b[:, 0:2] - a[:, 0:2]) / h, a[:, 2:4], atol=1e-5)
    assert np.allclose((b[:, 2:4] - a[:, 2:4]) / h, a[:, 4:6], atol=1e-5)


def test_hexagon_and_widened_ring():
    assert W.shape_radius(6) == 1.0 and W.shape_radius(48) > 1.5
    f = W.shape(0.0, 48)
    gaps = np.linalg.norm(f[:, :2] - np.roll(f[:, :2], 1, axis=0), axis=1)
    assert gaps.min() >= 0.199


@pytest.mark.parametrize("n", [7, 49, 1000])
def test_widened_ring_keeps_the_scaled_exp2_speed_and_reach(n):
    """At every N the slots move at 0.314 m/s about the leader and the followers start 0.85 m
    inside their circle, as in exp2_midge: a widened circle turning at 0.314 rad/s asked 10 m/s
    and a 16 m reach at N = 1000, which the tilt-limited followers could not fly."""
    f = W.shape(2.0, n - 1)
    assert np.allclose(np.linalg.norm(f[:, 2:4], axis=1), W.SHAPE_OMEGA)
    start = np.linalg.norm(W.starts(n)[1:, :2], axis=1)
    assert np.allclose(W.shape_radius(n - 1) - start, 0.85)
    toml = E.experiment("W2", n, "model.xml")
    assert f"omega = {W.shape_omega(n - 1):.17g}" in toml


# ---- cross-check arithmetic ---------------------------------------------------------------------
def test_divergence_time_and_lag():
    t = np.linspace(0, 2, 201)
    a = {"t": t.tolist(), "pos": np.zeros((201, 3)).tolist()}
    b = {"t": t.tolist(), "pos": np.c_[0.1 * t ** 2, np.zeros(201), np.zeros(201)].tolist()}
    assert X.divergence_time(a, b) == pytest.approx(math.sqrt(0.5), abs=2e-3)
    tt = np.arange(0, 0.5, 0.001)
    th = 1 + 0.3 * (1 - np.exp(-tt / 0.072))
    assert X.lag_time(tt, th) == pytest.approx(0.072, abs=1e-3)
    assert X.lag_discrete(0.072, 1e-6) == pytest.approx(0.072, rel=1e-4)
    w = 1 + (math.sqrt(1.3) - 1) * (1 - np.exp(-tt / 0.072))
    assert X.lag_time(tt, w ** 2) == pytest.approx(X.lag_on_speed(0.072, 1.3, w[-1] ** 2), abs=1e-3)


def test_predicted_extra_is_zero_at_rest_for_drag_terms():
    st = tier_states()["level_at_rest"]
    for peer in ("rotorpy", "pyflyt", "crazyflow"):
        lin, ang = X.predicted_extra(peer, st)
        assert np.allclose(lin, 0) and np.allclose(ang, 0)


def test_open_loop_schedule_is_yaw_neutral():
    for row in open_loop_schedule():
        _, tau = wrench(P.rotor_positions(), P.SIGNS, row)
        assert abs(tau[2]) < 1e-15
        assert sum(row) == pytest.approx(4 * P.derived()["hover_thrust"])


# ---- table writer -------------------------------------------------------------------------------
def test_fmt_and_spread():
    assert T.fmt(None) == "-" and T.fmt(float("nan")) == "-"
    assert T.fmt(12345.6) == "12,346" and T.fmt(0.012345) == "0.0123" and T.fmt(1.5) == "1.50"
    assert T.spread([3.0, 1.0, 2.0]) == "2.00 [1.00-3.00] (3)"
    assert T.spread([2.0]) == "2.00 (1)"


def test_speed_row_and_ratio():
    runs = [{"sim_s": 40.0, "wall_s": 2.0, "physics_steps": 40000},
            {"sim_s": 40.0, "wall_s": 4.0, "physics_steps": 40000},
            {"sim_s": 40.0, "wall_s": 1.0, "physics_steps": 40000}]
    s = T.speed_row(runs, 7)
    assert s["rtf_median"] == 20.0 and s["vsteps_median"] == 7 * 20000
    assert s["vehicle_seconds_per_s"] == 140.0
    assert T.ratio(140.0, 14.0) == pytest.approx(10.0)
    assert math.isnan(T.ratio(None, 1.0))


def test_markdown_table():
    text = T.markdown(["a", "b"], [["x", 1], ["y|z", 2]])
    assert text.splitlines() == ["| a | b |", "| --- | ---: |", "| x | 1 |", "| y/z | 2 |"]
    with pytest.raises(ValueError):
        T.markdown(["a", "b"], [["x"]])



def _cells(sim, n, wall, workloads=("W1", "W2")):
    return [{"sim": sim, "workload": w, "n": n, "controller": "own", "n_run": max(n, 2) if sim == "mjformation" else n,
             "runs": [{"sim_s": 40.0, "wall_s": wall, "physics_steps": 40000}]} for w in workloads]


def test_summary_text_follows_the_numbers():
    """The 'In short' prose is computed from the cells: who overtakes whom, and where."""
    import report
    speed = (_cells("mjformation", 1, 0.2) + _cells("mjformation", 49, 10.0)
             + _cells("crazyflow", 1, 7.0) + _cells("crazyflow", 49, 20.0))
    text = report.overtaking({"speed": speed})
    assert "No peer is faster" in text and "the closest is Crazyflow at 49 vehicles (2.00x)" in text
    speed = speed[:-2] + _cells("crazyflow", 49, 5.0)
    text = report.overtaking({"speed": speed})
    assert "Crazyflow overtakes" in text and "at 49 vehicles (every cell there, 2.0-2.0x faster)" in text
    table = [(("mjformation", False), ("rotorpy", False), 1.25), (("mjformation", False), ("rotorpy", True), None),
             (("mjformation", False), ("crazyflow", False), 1.3), (("mjformation", False), ("crazyflow", True), 3.34)]
    assert "after 1.2-1.3 s with the terms on" in report.open_loop_text(table)
    assert "for 3.3 s or more with them off" in report.open_loop_text(table)

# ---- the experiment files, checked by the runner itself when it is there ------------------------
@pytest.mark.parametrize("workload,n", [("W1", 1), ("W1", 7), ("W2", 7), ("W2", 49)])
def test_experiment_files(tmp_path, workload, n):
    model = tmp_path / "cfref.xml"
    model.write_text(P.mjcf())
    text = E.experiment(workload, n, str(model))
    toml = tmp_path / "x.toml"
    toml.write_text(text)
    assert f"followers = {max(n, 2) - 1}" in text
    cli = os.environ.get("MJF_CLI")
    if not cli:
        pytest.skip("MJF_CLI not set: the runner's check is skipped")
    r = subprocess.run([cli, "check", str(toml)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_the_regenerate_command_is_written_as_typed_in_a_checkout(tmp_path):
    import report
    root = PEERS.parent
    command = f"peers/run_peers.py --build {root / 'build'} --sizes 1,7 --out {tmp_path}"
    # A folder of the checkout becomes relative to it; one outside stays as given.
    assert report.checkout_command(command) == (
        f"peers/run_peers.py --build build --sizes 1,7 --out {tmp_path}")


class _Still:
    """A backend that holds its vehicles where they start (numpy only): for the timing protocol."""
    physics_hz, control_hz = 500.0, 100.0

    def make(self, starts):
        self.x = np.array(starts, float)

    def command(self, pos, vel, acc):
        pass

    def advance(self):
        pass

    def positions(self):
        return self.x

    def close(self):
        pass


@pytest.mark.parametrize("warmup,sim_s,steps", [(1, 0.99, 495), (2, 0.98, 490)])
def test_the_first_periods_are_timed_apart_from_the_stepping(warmup, sim_s, steps):
    sys.path.insert(0, str(PEERS / "workers"))
    import common
    run = common.fly(_Still, "W1", 4, "own", 1.0, 60.0, warmup_periods=warmup)
    assert run["sim_s"] == pytest.approx(sim_s) and run["physics_steps"] == steps
    assert run["warmup_s"] is not None and run["error_final"] == 0.0

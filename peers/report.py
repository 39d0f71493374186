# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""docs/PEERS.md and its figure from peers/out/results.json (run_peers.py writes both)."""

import math
import os
from pathlib import Path

import numpy as np

from peerlib import crosscheck as X
from peerlib import params as P
from peerlib.scenarios import tier_states
from peerlib.tables import fmt, markdown, ratio, speed_row, spread

NAMES = {"mjformation": "mjformation", "rotorpy": "RotorPy", "pyflyt": "PyFlyt", "crazyflow": "Crazyflow"}
INTEGRATOR = {"mjformation": "semi-implicit Euler, 1 kHz (MuJoCo)",
              "rotorpy": "RK45 (scipy solve_ivp) over each 10 ms step",
              "pyflyt": "Bullet, 240 Hz; motor state explicit Euler",
              "crazyflow": "explicit Euler, 500 Hz, float32 (JAX default)"}
LAGGED = {"mjformation": "thrust (MuJoCo `filter` actuator: d act/dt = (ctrl - act) / tau)",
          "rotorpy": "rotor speed w (thrust = k_eta w^2)",
          "pyflyt": "throttle = w / w_max (thrust = T_max throttle^2)",
          "crazyflow": "rotor speed in rpm (thrust = k rpm^2)"}


def _dyn(results, sim, bare=False):
    d = results["dynamics"].get(sim)
    if not d:
        return None
    for j in d.get("jobs", []):
        if j.get("job", {}).get("kind") == "dynamics" and bool(j.get("bare", j["job"].get("bare", False))) == bare:
            return j
    return None


def speed_section(results):
    cells = results["speed"]
    if not cells:
        return "Not measured in this invocation (`--skip-speed`).\n"
    ours = {}
    for c in cells:
        if c["sim"] == "mjformation" and c.get("runs"):
            ours[(c["workload"], c["n"])] = speed_row(c["runs"], c.get("n_run", c["n"]))
    rows = []
    for c in cells:
        name = NAMES[c["sim"]]
        n_run = c.get("n_run", c["n"])
        label = f"{c['n']}" if n_run == c["n"] else f"{c['n']} (flown as {n_run})"
        ctrl = {"own": "own position controller", "smc": "discrete SMC (48) in Python",
                "smc (48)": "smc_discrete (48)", "hover": "hover guidance"}.get(c["controller"], c["controller"])
        if c.get("error") and not c.get("runs"):
            rows.append([name, c["workload"], label, ctrl] + ["-"] * 7 + [f"failed: {c['error'][:160]}"])
            continue
        runs = c["runs"]
        s = speed_row(runs, n_run)
        ref = ours.get((c["workload"], c["n"]))
        r = ratio(ref["vehicle_seconds_per_s"], s["vehicle_seconds_per_s"]) if ref else float("nan")
        sim_s = [x["sim_s"] for x in runs]
        short = min(sim_s) < results["args"]["duration"] - 0.1
        errs = [x.get("error_mean_25_40") for x in runs]
        err_txt = spread(errs, 2) if any(e is not None for e in errs) else (
            f"{fmt(runs[0].get('error_final'), 2)} at {fmt(sim_s[0], 3)} s" if runs else "-")
        setup = [x.get("setup_s") for x in runs]
        warm = [x.get("warmup_s") for x in runs if x.get("warmup_s") is not None]
        rows.append([name, c["workload"], label, ctrl, fmt(c.get("physics_hz") or 0, 3),
                     fmt(statistics_median(sim_s), 3) + (" (budget)" if short else ""),
                     spread([x["wall_s"] for x in runs], 3),
                     fmt(statistics_median(setup), 2) + (" + " + fmt(statistics_median(warm), 2) if warm else ""),
                     spread(s["rtf"], 3), spread(s["vsteps"], 3),
                     "1" if c["sim"] == "mjformation" else fmt(r, 3), err_txt])
    head = ["simulator", "work", "N", "controller", "physics Hz", "sim s / run", "wall s: median [range] (runs)",
            "setup + first period s", "real-time factor", "vehicle-steps / s",
            "mjformation x faster", "error m, mean on [25, 40] s"]
    return markdown(head, rows, ["l", "l", "r", "l"] + ["r"] * 8) + "\n"


def statistics_median(xs):
    xs = [x for x in xs if x is not None]
    return float(np.median(xs)) if xs else float("nan")


def accel_section(results):
    base = _dyn(results, "mjformation")
    if not base or "accel" not in base:
        return "mjformation's tier (a) did not run: " + str((results["dynamics"].get("mjformation") or {}).get("process_error")) + "\n"
    states = {"level_at_rest": "level, at rest", "tilted_moving": "tilted (0.2, -0.1, 0.3 rad), v = (1, -0.5, 0.3) m/s, w = (0.5, -0.4, 0.3) rad/s"}
    st_all = tier_states()
    out = []
    for key, label in states.items():
        rows = []
        ml, ma = np.array(base["accel"][key]["lin"]), np.array(base["accel"][key]["ang"])
        for sim in ["mjformation"] + [p for p in ("rotorpy", "pyflyt", "crazyflow") if p in results["dynamics"]]:
            for bare in ((False,) if sim == "mjformation" else (False, True)):
                j = _dyn(results, sim, bare)
                if not j or "accel" not in j:
                    err = (j or {}).get("error") or (results["dynamics"].get(sim) or {}).get("process_error")
                    rows.append([NAMES[sim] + (" (drag/gyro off)" if bare else ""), "-", "-", "-", "-", "-", "-", f"failed: {err}"])
                    continue
                lin, ang = np.array(j["accel"][key]["lin"]), np.array(j["accel"][key]["ang"])
                pl, pa = X.predicted_extra(sim, st_all[key]) if not bare else (np.zeros(3), np.zeros(3))
                dl, da = lin - ml, ang - ma
                rows.append([NAMES[sim] + (" (drag/gyro off)" if bare else ""),
                             " ".join(f"{v:+.4f}" for v in lin), " ".join(f"{v:+.3f}" for v in ang),
                             f"{np.linalg.norm(dl):.2e}", f"{np.linalg.norm(da):.2e}",
                             f"{np.linalg.norm(pl):.2e} / {np.linalg.norm(pa):.2e}",
                             f"{np.linalg.norm(dl - pl):.1e} / {np.linalg.norm(da - pa):.1e}",
                             j.get("accel", {}).get(key, {}).get("note", "")])
        out.append(f"**{label}**, thrusts (1.05, 0.95, 1.02, 0.98) x hover on r1..r4:\n\n" + markdown(
            ["simulator", "a world (m/s^2)", "angular acc. body (rad/s^2)", "|a - a_mjf|", "|alpha - alpha_mjf|",
             "predicted by its extra terms (a / alpha)", "residual (a / alpha)", "how"],
            rows, ["l", "l", "l", "r", "r", "r", "r", "l"]))
    return "\n\n".join(out) + "\n"


def divergence(results):
    base = _dyn(results, "mjformation")
    table, curves = [], {}
    if not base or not base.get("open_loop"):
        return None, curves
    sims = ["mjformation"] + [p for p in ("rotorpy", "pyflyt", "crazyflow") if p in results["dynamics"]]
    runs = {}
    for s in sims:
        for bare in ((False,) if s == "mjformation" else (False, True)):
            j = _dyn(results, s, bare)
            if j and j.get("open_loop"):
                runs[(s, bare)] = j["open_loop"]
    keys = list(runs)
    for a in range(len(keys)):
        for b in range(a + 1, len(keys)):
            ka, kb = keys[a], keys[b]
            if ka[1] != kb[1] and ka[0] != "mjformation" and kb[0] != "mjformation":
                continue
            t = X.divergence_time(runs[ka], runs[kb])
            table.append((ka, kb, t))
            if ka[0] == "mjformation":
                curves[kb] = X.separation(runs[ka], runs[kb])
    return table, curves


def figure(curves, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4.5))
    colors = {"rotorpy": "tab:blue", "pyflyt": "tab:orange", "crazyflow": "tab:green"}
    for (sim, bare), (t, sep) in sorted(curves.items()):
        ax.semilogy(t, np.maximum(sep, 1e-9), color=colors.get(sim, "k"), ls="--" if bare else "-",
                    label=f"{NAMES[sim]}{' (drag/gyro off)' if bare else ''}")
    ax.axhline(0.05, color="k", lw=0.8)
    ax.text(0.05, 0.055, "5 cm", fontsize=9)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("|p_peer - p_mjformation| (m)")
    ax.set_ylim(1e-8, 10)
    ax.set_title("Open loop, same rotor thrust sequence from hover: distance from mjformation")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def lag_section(results):
    rows = []
    h = P.derived()["hover_thrust"]
    tau = P.REFERENCE["tau_m"]
    for sim in ["mjformation", "rotorpy", "pyflyt", "crazyflow"]:
        j = _dyn(results, sim)
        if not j or not j.get("rotor_step"):
            continue
        rs = j["rotor_step"]
        t63 = X.lag_time(rs["t"], rs["thrust"])
        final = rs["thrust"][-1] / h
        dt = {"mjformation": 0.001, "rotorpy": 0.0, "pyflyt": 1 / 240, "crazyflow": 1 / 500}[sim]
        if sim == "mjformation":
            pred = X.lag_discrete(tau, dt)
            how = f"first order on thrust, Euler at {dt * 1000:g} ms: dt ln(1-0.632) / ln(1 - dt/tau)"
        else:
            pred = X.lag_on_speed(tau, 1.3, final)
            if dt:
                pred *= X.lag_discrete(tau, dt) / tau
                how = f"first order on speed (thrust ~ w^2), Euler at {dt * 1000:.3g} ms"
            else:
                how = "first order on speed (thrust ~ w^2), RK45"
        rows.append([NAMES[sim], LAGGED[sim], fmt(t63 * 1000, 3), fmt(pred * 1000, 3), fmt(final, 4), how])
    return markdown(["simulator", "what lags", "63.2 % time, measured (ms)", "predicted (ms)",
                     "thrust at 0.4 s / hover", "prediction"], rows, ["l", "l", "r", "r", "r", "l"]) + "\n"


def write(results, doc, out):
    doc = Path(doc)
    fig_path = doc.parent / "peers_divergence.png"
    table, curves = divergence(results)
    if curves:
        figure(curves, fig_path)
    m = results["machine"]
    ref, d = results["reference"], results["derived"]
    lines = ["# Side by side with the peers: RotorPy, PyFlyt, Crazyflow", "",
             "Generated by the peers harness (`peers/`, issue 37) on "
             f"{results['started']}; regenerate everything (installs, runs, this file, the figure) with:", "",
             "```bash", f"/usr/bin/python3 {results['command']}", "```", "",
             "(`--build DIR` names the mjformation build whose runner is timed; `--report-only` rewrites this "
             "file from `peers/out/results.json`.) The harness is not part of `.ci/run` (it installs from PyPI); "
             "CI runs `peers/tests` (the table writer, the parameter matching, the experiment files) through "
             "ctest as `peers_pytest`.", "",
             "## Machine, versions, load", "",
             f"- {m.get('cpu')}, {m.get('nproc')} cores shared with other work, {m.get('os')}, "
             f"Python {m.get('python')} (virtual environments made from /usr/bin/python3).",
             f"- mjformation: `{results.get('mjformation_version')}`, runner `{results['binary']}`.",
             f"- Load average (1, 5, 15 min) at the start {tuple(round(x, 2) for x in m['loadavg'])}, at the end "
             f"{tuple(round(x, 2) for x in m.get('loadavg_end', m['loadavg']))}; during the speed cells: "
             + (", ".join(f"{x[0]:.1f}" for x in m.get("load_during", [])) or "-") + " (1-min).",
             "- Peers, pinned (peers/locks/*.txt, every dependency at an exact version; `--no-deps` installs):"]
    for name, inst in results["install"].items():
        lines.append(f"  - {name}: " + (", ".join(inst["pins"]) if inst["ok"] else f"**install failed**: {inst['error']}"))
    lines += ["", "## The vehicle, matched", "",
              "One Crazyflie-class reference (peers/peerlib/params.py: RotorPy 3.0's `crazyflie_params`) "
              "translated into each simulator's own parameters:", "",
              markdown(["quantity", "value", "mjformation (MJCF)", "RotorPy", "PyFlyt (URDF + YAML)", "Crazyflow (params)"], [
                  ["mass", f"{ref['mass']} kg", "inertial mass", "mass", "base_link mass", "mass"],
                  ["inertia", f"{ref['ixx']:.3g}, {ref['iyy']:.3g}, {ref['izz']:.3g} kg m^2", "diaginertia", "Ixx Iyy Izz", "base_link inertia", "J"],
                  ["rotors", f"arm {ref['arm']} m at 45 deg (x, y = +-{d['offset']:.4f} m)", "sites r1..r4", "rotor_pos", "prop1..4 links (order matched)", "L, mixing_matrix"],
                  ["thrust", f"k_eta {ref['k_eta']:.3g} N/(rad/s)^2, max {d['thrust_max']:.4f} N/rotor (T/W {d['thrust_to_weight']:.2f})", "ctrlrange 0..max, gain 1", "k_eta, rotor_speed_max", "thrust_coef, total_thrust", "rpm2thrust = k_eta (2 pi / 60)^2"],
                  ["yaw reaction", f"k_m {ref['k_m']:.3g} (yaw arm {d['yaw_arm']:.4f} m)", "gear[5] = +-k_m/k_eta", "k_m, rotor_directions", "torque_coef", "rpm2torque"],
                  ["motor lag", f"tau {ref['tau_m']} s", "dyntype filter, dynprm tau", "tau_m", "tau", "rotor_dyn_coef = [1/tau, 0, 1/tau, 0]"],
              ], ["l"] * 6), "",
              "Izz is 2.85e-5 kg m^2 where RotorPy writes 2.89e-5: RotorPy's value breaks Ixx + Iyy >= Izz, which "
              "no rigid body can (Bullet sets the inertia of such a link to zero, with a warning, and MuJoCo's "
              "compiler refuses it); 2.85e-5 is the nearest value both accept. Each peer keeps its own model terms "
              "that have no counterpart here; the cross-check switches them off in a second, \"drag/gyro off\" run:", ""]
    for k, v in results["unmatched"].items():
        lines.append(f"- **{NAMES[k]}**: {v}.")
    lines += ["", "## Speed: W1 and W2", "",
              "W1: N vehicles hover 0.5 m up on a 0.3 m grid for 40 s. W2: exp2_midge's scaled Exp 2 (leader on a "
              "2 m circle at 0.157 rad/s, followers on a 1 m circle turning at 0.314 rad/s: a hexagon for 6), the "
              "followers flown by each simulator's own position controller (the slot's position, velocity and "
              "acceleration as reference where the controller takes them) and, where the peer takes an "
              "acceleration reference, by the discrete sliding-mode law (48) ported to numpy "
              "(peers/peerlib/workload.py, the same gains as the `smc_discrete` plugin, its output capped at "
              "g tan(0.78) as mjformation's attitude plugin caps tilt). No rendering; one process per peer and "
              "cell; single-threaded BLAS, numba and XLA. Wall time is the stepping loop only: the simulator's "
              "construction (setup) and its first control period (JIT compilation in Crazyflow and PyFlyt's numba) "
              "are reported apart. mjformation's wall time is `summary.json`'s `timing.wall_time_s` of "
              "`mjformation run --no-render` (recording timeseries.csv at 10 Hz); its followers fly the "
              "`pd_cascade` attitude plugin (see below). The runner needs one follower at least: N = 1 is flown "
              "as N = 2, and the ratio compares vehicle-seconds simulated per wall second (N x real-time factor), "
              "which for equal N is the ratio of real-time factors. A peer run that would exceed "
              f"{results['args']['wall_budget']:g} s of wall time stops there (\"budget\" in the sim-s column).", "",
              speed_section(results), "",
              "## Dynamics cross-check", "",
              "mjformation's side is the `scene.xml` the runner composed for this vehicle, stepped by MuJoCo "
              f"{(results['dynamics'].get('mjformation') or {}).get('mujoco', '?')} from PyPI with the model's "
              "Euler integrator at 1 kHz (as the runner steps it). Per-rotor thrusts are given in newtons and "
              "converted through each simulator's own thrust map (rotor speed for RotorPy, PWM for PyFlyt, rpm "
              "for Crazyflow) with the rotor state already at that speed.", "",
              "### (a) Accelerations from identical states and thrusts", "",
              accel_section(results), ""]
    lines += ["### (b) Open loop: time until positions differ by 5 cm", "",
              "From level hover at 0.5 m (rotors at hover speed), every simulator gets the same per-rotor thrust "
              "sequence for 4 s, changed every 50 ms (a common divisor of the four physics rates): hover plus "
              "0.1 % and 0.07 % differential terms that roll and pitch the vehicle back and forth. Positions are "
              "compared on a 1 ms grid (linear interpolation of each simulator's own samples).", ""]
    if table is not None:
        rows = [[NAMES[a[0]] + (" (off)" if a[1] else ""), NAMES[b[0]] + (" (off)" if b[1] else ""),
                 fmt(t, 3) if t is not None else "> 4 (never)"] for a, b, t in table]
        lines += [markdown(["simulator", "against", "5 cm apart after (s)"], rows, ["l", "l", "r"]), "",
                  f"![open-loop divergence]({fig_path.name})", ""]
    lines += ["### (c) A single rotor step: the motor lag each shows", "",
              "Rotor r1's command steps from hover thrust to 1.3 x hover at t = 0 (the others stay at hover, the "
              "vehicle is free), and its thrust is read from the simulator's own motor state.", "",
              lag_section(results), ""]
    doc.write_text("\n".join(lines) + "\n" + (EXPLAIN if EXPLAIN else ""))


EXPLAIN = ""

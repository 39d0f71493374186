# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The peers report (OUT/PEERS.md, or docs/PEERS.md with --doc) and its figure from one
invocation's results.json (run_peers.py writes both). It states only what that invocation measured."""

import math
import os
from pathlib import Path

import numpy as np

from peerlib import crosscheck as X
from peerlib import params as P
from peerlib import workload as W
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


def checkout_command(command: str) -> str:
    """The harness's command as a user types it in a checkout: absolute paths inside the
    repository (a `--build` folder given as /path/to/checkout/build) written relative to it."""
    root = Path(__file__).resolve().parent.parent
    words = []
    for word in command.split(" "):
        path = Path(word)
        if path.is_absolute() and (path == root or root in path.parents):
            word = os.path.relpath(path, root)
        words.append(word)
    return " ".join(words)

def _dyn(results, sim, bare=False):
    d = results["dynamics"].get(sim)
    if not d:
        return None
    for j in d.get("jobs", []):
        if j.get("job", {}).get("kind") == "dynamics" and bool(j.get("bare", j["job"].get("bare", False))) == bare:
            return j
    return None


def ratios(results, cells=False):
    """{peer: {N: [mjformation x faster, one per cell (W1, W2, every controller)]}}; with cells,
    (workload, controller, ratio) per cell."""
    ours = {(c["workload"], c["n"]): speed_row(c["runs"], c.get("n_run", c["n"]))
            for c in results["speed"] if c["sim"] == "mjformation" and c.get("runs")}
    out = {}
    for sim in ("rotorpy", "pyflyt", "crazyflow"):
        for n in sorted({c["n"] for c in results["speed"]}):
            rs = [(c["workload"], c["controller"], ratio(ours[(c["workload"], n)]["vehicle_seconds_per_s"],
                                                         speed_row(c["runs"], c["n"])["vehicle_seconds_per_s"]))
                  for c in results["speed"] if c["sim"] == sim and c["n"] == n and c.get("runs")
                  and (c["workload"], n) in ours]
            rs = [r for r in rs if not math.isnan(r[2])]
            if rs:
                out.setdefault(sim, {})[n] = rs if cells else [r[2] for r in rs]
    return out


def summary(results):
    """One line per peer: the range of 'mjformation x faster' over the cells, per N."""
    out = []
    for sim, per_n in ratios(results).items():
        parts = [f"N = {n}: " + (f"{fmt(rs[0], 3)}x" if len(set(rs)) == 1 else f"{fmt(min(rs), 3)}-{fmt(max(rs), 3)}x")
                 for n, rs in per_n.items()]
        out.append(f"- mjformation against {NAMES[sim]}: " + "; ".join(parts) +
                   " (below 1: the peer is faster).")
    return "\n".join(out)


def overtaking(results):
    """Which peer, if any, is faster than mjformation's runner, and where: from the ratios."""
    rs, cells = ratios(results), ratios(results, cells=True)
    runner = "mjformation's runner (1 kHz, full pipeline, recording)"
    out = ["Crazyflow steps all drones of a world as one JAX array; RotorPy and PyFlyt step vehicles one by one "
           "in Python."]
    faster = []
    for sim in ("crazyflow", "rotorpy", "pyflyt"):
        per_n = rs.get(sim, {})
        over = [n for n in sorted(per_n) if min(per_n[n]) < 1]
        if not over:
            continue
        n0 = over[0]
        k, m = sum(r < 1 for r in per_n[n0]), len(per_n[n0])
        if k == m:
            faster.append(f"{NAMES[sim]} overtakes {runner} at {n0} vehicles (every cell there, "
                          f"{fmt(1 / max(per_n[n0]), 2)}-{fmt(1 / min(per_n[n0]), 2)}x faster)")
        else:
            label = {"own": "its own controller", "smc": "the SMC law"}
            cl = cells[sim][n0]
            yes = [f"{w} with {label.get(c, c)} (mjformation {fmt(r, 3)}x)" for w, c, r in cl if r < 1]
            no = [f"{w} with {label.get(c, c)} ({fmt(r, 3)}x)" for w, c, r in cl if r >= 1]
            join = lambda xs, last: xs[0] if len(xs) == 1 else ", ".join(xs[:-1]) + f" {last} " + xs[-1]
            faster.append(f"{NAMES[sim]} is faster than {runner} at {n0} vehicles in {k} of its {m} cells: "
                          + join(yes, "and") + "; not in " + join(no, "or"))
    if faster:
        out.append("; ".join(faster) + ".")
    elif rs:
        sim, n, r = min(((sim, n, min(v)) for sim, per_n in rs.items() for n, v in per_n.items()),
                        key=lambda x: x[2])
        out.append(f"No peer is faster than {runner} at any size measured; the closest is {NAMES[sim]} at "
                   f"{n} vehicles ({fmt(r, 3)}x).")
    return " ".join(out)


def open_loop_ranges(table):
    """(min, max) time to 5 cm of the peers against mjformation with their terms on, and the
    shortest with them off (None: none parted within the 4 s)."""
    on = [t for a, b, t in (table or []) if a[0] == "mjformation" and not b[1] and t is not None]
    off = [t for a, b, t in (table or []) if a[0] == "mjformation" and b[1]]
    off_min = min((t for t in off if t is not None), default=None)
    return (min(on) if on else None, max(on) if on else None), off_min, bool(off)


def open_loop_text(table):
    (lo, hi), off_min, any_off = open_loop_ranges(table)
    if lo is None:
        return "in open-loop flight no peer parted from mjformation by 5 cm within 4 s (tier (b))"
    rng = fmt(lo, 2) if fmt(lo, 2) == fmt(hi, 2) else f"{fmt(lo, 2)}-{fmt(hi, 2)}"
    txt = f"in open-loop flight the positions part by 5 cm after {rng} s with the terms on"
    if any_off:
        txt += (", and stay within 5 cm for the whole 4 s with them off" if off_min is None else
                f", and stay within 5 cm for {fmt(off_min, 2)} s or more with them off")
    return txt + " (tier (b))"


def speed_section(results, sizes=None):
    """The speed table: every cell, or those of the vehicle counts in `sizes`."""
    cells = [c for c in results["speed"] if sizes is None or c["n"] in sizes]
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
        if c.get("sets"):
            ctrl += "; " + ", ".join(f"`--set {x}`" for x in c["sets"])
        if c.get("error") and not c.get("runs"):
            rows.append([name, c["workload"], label, ctrl] + ["-"] * 7 + [f"failed: {c['error'][:160]}"])
            continue
        runs = c["runs"]
        s = speed_row(runs, n_run)
        ref = ours.get((c["workload"], c["n"]))
        r = ratio(ref["vehicle_seconds_per_s"], s["vehicle_seconds_per_s"]) if ref else float("nan")
        sim_s = [x["sim_s"] for x in runs]
        short = min(sim_s) < c.get("duration", results["args"]["duration"]) - 0.1
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
        why = (results["dynamics"].get("mjformation") or {}).get("process_error") or "its MuJoCo worker did not run"
        return f"mjformation's side of tier (a) has no result ({why}): no comparison.\n"
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


def batch_section(results):
    b = results.get("batch")
    if not b:
        return "Batched worlds: not measured in this invocation.\n"
    ours, cf = b["mjformation"], b["crazyflow"]
    rows = [["mjformation `sweep --jobs 2` (2 threads)", f"{ours['runs']} runs of 40 s", fmt(ours["wall_s"], 3),
             fmt(ours["runs_per_hour"], 3), ours.get("error") or ""]]
    if "wall_s" in cf:
        rows.append([f"Crazyflow, {cf['worlds']} worlds in one Sim (XLA on 2 threads)",
                     f"{fmt(cf['sim_s'], 3)} s simulated, scaled to 40 s",
                     f"{fmt(cf['setup_s'], 3)} setup + {fmt(cf['warmup_s'], 3)} first period + {fmt(cf['wall_s'], 3)} stepping",
                     fmt(cf.get("runs_per_hour_40s"), 3), f"mean slot error at the end {fmt(cf.get('final_error'), 2)} m"])
    else:
        rows.append(["Crazyflow batched", "-", "-", "-", f"failed: {cf.get('error')}"])
    return ("**Batched**: W2 (N = 7) 40-s runs per hour on both cores, one invocation. RotorPy's batched "
            "vehicle (`BatchedMultirotor`) needs PyTorch, which RotorPy 3.0 does not install and the harness "
            "does not add: not measured.\n\n" + markdown(["how", "work", "wall s", "40-s runs per hour", "note"], rows,
                                                            ["l", "l", "r", "r", "l"]) + "\n")


SPEED_NOTES = """Reading the table:
- *Error* is the mean distance of the followers from their slots (W2) or of the vehicles from their hover
  points (W1) over [25, 40] s, sampled at 10 Hz, computed by the same function for every simulator
  (peers/peerlib/workload.py); it says whether the run flew the work, not how good a controller is.
  A run cut by the wall budget gives its error at its last time instead.
- PyFlyt has no flight mode that takes an acceleration (mode 6 takes velocities, 7 positions), so the
  Python SMC law, whose output is an acceleration, is not flown there; its "own position controller" row
  gets positions only (no feed-forward), which is why it trails the turning slots.
{rotorpy_hover}: each 10 ms step is a fresh
  `solve_ivp` RK45 call, and at an exact equilibrium (W1 starts every vehicle at hover, rotors at hover
  speed, and RotorPy holds it to the last digit: error 0) scipy's initial-step rule takes h0 = 1e-6 s when
  the derivative is below 1e-5 and RK45 grows the step at most tenfold per step, so each call takes
  several more internal steps (consistent with the cost; the steps were not counted).
{crazyflow_errors}
- Crazyflow steps all drones of a world as one array: {crazyflow_growth}; its setup and JIT compilation
  (the "first period") cost seconds, once per Sim.
- mjformation's followers fly `pd_cascade`. With the `geometric` attitude plugin, whose loops are derived
  from the vehicle (rate_bw <= 1 / tau = 13.9 rad/s for the 72 ms motors, att_bw 3.0 rad/s, z_bw 1.2 rad/s),
  the discrete SMC law (T = 0.05 s, gain 1 / (k2 T) = 20 1/s on the velocity error) outruns the tilt loop on
  this slow-motor vehicle: in W2 at N = 7 the followers oscillate with tilts up to 0.72 rad, follower 5
  touches the ground at 3.6 s (15 safety events in all), and the slot error stays at 0.49 m on [25, 40] s
  against 0.008 m with `pd_cascade` (`mjformation run peers/out/W2_n7.toml --set
  'attitude={plugin="geometric"}'` reproduces it; one run, checked by hand on MuJoCo 4.0.1 on 2026-12-05, not
  re-run by the harness). That is a finding about our stock plugin on a slow-motor vehicle,
  not a peer's. RotorPy's SE3 controller (kp_att 310, kd_att 57) carries the same law.
"""


def _cell(results, sim, workload, n, ctrl):
    for c in results["speed"]:
        if (c["sim"], c["workload"], c["n"], c["controller"]) == (sim, workload, n, ctrl) and c.get("runs"):
            return c
    return None


def speed_notes(results):
    """SPEED_NOTES with its measured statements filled from this invocation's cells."""
    sizes = sorted({c["n"] for c in results["speed"]})
    # RotorPy: W1 against W2 real-time factor, own controller, per N
    lower, higher = [], []
    for n in sizes:
        a, b = _cell(results, "rotorpy", "W1", n, "own"), _cell(results, "rotorpy", "W2", n, "own")
        if a and b:
            ra = speed_row(a["runs"], n)["rtf_median"]
            rb = speed_row(b["runs"], n)["rtf_median"]
            (lower if ra < rb else higher).append(f"N = {n}: {fmt(ra, 3)} against {fmt(rb, 3)}")
    if lower and not higher:
        rotorpy_hover = ("- RotorPy hovers (W1) at a lower real-time factor than it flies W2 at every N (" +
                         "; ".join(lower) + ")")
    elif lower:
        rotorpy_hover = ("- RotorPy hovers (W1) at a lower real-time factor than it flies W2 at " +
                         "; ".join(lower) + " (not at " + "; ".join(higher) + ")")
    else:
        rotorpy_hover = ("- RotorPy's W1 (hover) is not slower than its W2 in this invocation; where it is, the "
                         "reason is this")
    # Crazyflow: its own controller against the SMC law in W2
    own, smc, own_n = [], [], []
    for n in sizes:
        for ctrl, acc in (("own", own), ("smc", smc)):
            c = _cell(results, "crazyflow", "W2", n, ctrl)
            if c:
                e = [x["error_mean_25_40"] for x in c["runs"] if x.get("error_mean_25_40") is not None
                     and not math.isnan(x["error_mean_25_40"])]
                if e:
                    acc.append(float(np.median(e)))
                    if ctrl == "own":
                        own_n.append(str(n))
    if own and smc:
        crazyflow_errors = (
            "- Crazyflow's own state controller (Mellinger, with its own mass 0.029 kg and gains) trails the turning\n"
            f"  slots by {fmt(min(own), 2)}-{fmt(max(own), 2)} m in W2 (N = {', '.join(own_n)}); "
            f"the same simulator under the SMC law keeps them to {fmt(min(smc), 2)}-{fmt(max(smc), 2)} m.")
    else:
        crazyflow_errors = "- Crazyflow's W2 errors: not measured in this invocation."
    # Crazyflow: vehicle-steps per second from the smallest N to 7 (or the next size)
    growth = []
    if len(sizes) > 1:
        n0, n1 = sizes[0], (7 if 7 in sizes[1:] else sizes[1])
        for w in ("W1", "W2"):
            a, b = _cell(results, "crazyflow", w, n0, "own"), _cell(results, "crazyflow", w, n1, "own")
            if a and b:
                g = speed_row(b["runs"], n1)["vsteps_median"] / speed_row(a["runs"], n0)["vsteps_median"]
                growth.append(f"{fmt(g, 2)}-fold in {w}")
        crazyflow_growth = (f"from N = {n0} to {n1} ({n1 / n0:g} times the vehicles) its vehicle-steps per second grow "
                            + " and ".join(growth)) if growth else "its cost per vehicle falls with N"
    else:
        crazyflow_growth = "its cost per vehicle falls with N (one size measured here)"
    return (SPEED_NOTES.replace("{rotorpy_hover}", rotorpy_hover).replace("{crazyflow_errors}", crazyflow_errors)
            .replace("{crazyflow_growth}", crazyflow_growth))


def accel_agreement(results):
    """The largest |a - a_mjf| (m/s^2, rad/s^2) of the peers with their extra terms off, and the
    largest residual once the predicted extra terms are subtracted with them on; None when tier (a)
    has no result on both sides."""
    base = _dyn(results, "mjformation")
    if not base or "accel" not in base:
        return None
    off, residual, states = [0.0, 0.0], [0.0, 0.0], tier_states()
    found = False
    for sim in ("rotorpy", "pyflyt", "crazyflow"):
        for bare in (False, True):
            j = _dyn(results, sim, bare)
            if not j or "accel" not in j:
                continue
            found = True
            for key in base["accel"]:
                dl = np.array(j["accel"][key]["lin"]) - np.array(base["accel"][key]["lin"])
                da = np.array(j["accel"][key]["ang"]) - np.array(base["accel"][key]["ang"])
                if bare:
                    off = [max(off[0], np.linalg.norm(dl)), max(off[1], np.linalg.norm(da))]
                else:
                    pl, pa = X.predicted_extra(sim, states[key])
                    residual = [max(residual[0], np.linalg.norm(dl - pl)),
                                max(residual[1], np.linalg.norm(da - pa))]
    return (off, residual) if found else None


def dynamics_summary(results, table):
    """What the dynamics tiers of this invocation measured, in one or two sentences."""
    if not results["dynamics"]:
        return "The dynamics tiers (a)-(c) did not run in this invocation (`--skip-dynamics`)."
    agreement = accel_agreement(results)
    if agreement is None:
        text = "Tier (a) has no accelerations from both mjformation and a peer in this invocation"
    else:
        (off_a, off_w), (res_a, res_w) = agreement
        text = (f"With the peers' own aerodynamic and gyroscopic terms off, accelerations differ from "
                f"mjformation's by at most {off_a:.1e} m/s^2 and {off_w:.1e} rad/s^2; with them on, what "
                f"those terms do not account for is at most {res_a:.1e} m/s^2 and {res_w:.1e} rad/s^2 "
                "(tier (a))")
    if table is None:
        return text + "; tier (b) has no open-loop result."
    return text + "; " + open_loop_text(table) + "."


def in_short(results, table):
    """The report's opening lines: the speed ratios and the dynamics, as measured by this run."""
    lines = ["## In short", ""]
    if results["speed"]:
        lines += ["How many times faster mjformation flies the same vehicle-seconds (W1 and W2, every "
                  "controller), measured in this invocation on a shared machine (its load average below):",
                  "", summary(results), "", overtaking(results) + " " + dynamics_summary(results, table)]
    else:
        lines += ["Speed: not measured in this invocation (`--skip-speed`). " + dynamics_summary(results, table)]
    return lines + [""]


def header(results, doc):
    regenerate = checkout_command(results["command"])
    return ["# Side by side with the peers: RotorPy, PyFlyt, Crazyflow", "",
            "Generated by the peers harness (`peers/`, issue 37) on "
            f"{results['started']}; regenerate everything (installs, runs, this file, the figure) with:", "",
            "```bash", f"/usr/bin/python3 {regenerate}", "```", "",
            "(`--build DIR` names the mjformation build whose runner is timed; `--report-only` rewrites the "
            "report from `OUT/results.json`; without `--doc` it goes to `OUT/PEERS.md`.) The harness is not "
            "part of `.ci/run` (it installs from PyPI); CI runs `peers/tests` (the table writer, the parameter "
            "matching, the experiment files) through ctest as `peers_pytest`.", ""]


def machine_lines(results):
    m = results["machine"]
    lines = ["## Machine, versions, load", "",
             f"- {m.get('cpu')}, {m.get('nproc')} cores shared with other work, {m.get('os')}, "
             f"Python {m.get('python')} (virtual environments made from /usr/bin/python3).",
             f"- mjformation: `{results.get('mjformation_version')}`, runner "
             f"`{checkout_command(results['binary'])}`.",
             f"- Load average (1, 5, 15 min) at the start {tuple(round(x, 2) for x in m['loadavg'])}, at the end "
             f"{tuple(round(x, 2) for x in m.get('loadavg_end', m['loadavg']))}; during the speed cells: "
             + (", ".join(f"{x[0]:.1f}" for x in m.get("load_during", [])) or "-") + " (1-min).",
             "- Peers, pinned (peers/locks/*.txt, every dependency at an exact version; `--no-deps` installs):"]
    for name, inst in results["install"].items():
        lines.append(f"  - {name}: " + (", ".join(inst["pins"]) if inst["ok"] else f"**install failed**: {inst['error']}"))
    return lines


def vehicle_lines(results):
    ref, d = results["reference"], results["derived"]
    lines = []
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
    return lines


def speed_lines(results):
    lines = []
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
              speed_section(results), "", batch_section(results)]
    if results["speed"]:
        lines.append(speed_notes(results))
    return lines + [""]


def dynamics_lines(results, table, fig_path):
    if not results["dynamics"]:
        return ["## Dynamics cross-check", "", "Not run in this invocation (`--skip-dynamics`).", ""]
    engine = (results["dynamics"].get("mjformation") or {}).get("mujoco")
    side = (f"stepped by MuJoCo {engine} from PyPI" if engine else
            "which did not run in this invocation (its worker: "
            f"{(results['dynamics'].get('mjformation') or {}).get('process_error') or 'not installed'})")
    lines = ["## Dynamics cross-check", "",
             "mjformation's side is the `scene.xml` the runner composed for this vehicle, " + side +
             ", with the model's Euler integrator at 1 kHz (as the runner steps it). Per-rotor thrusts are "
             "given in newtons and converted through each simulator's own thrust map (rotor speed for RotorPy, "
             "PWM for PyFlyt, rpm for Crazyflow) with the rotor state already at that speed.", "",
             "### (a) Accelerations from identical states and thrusts", "",
             accel_section(results), ""]
    lines += ["### (b) Open loop: time until positions differ by 5 cm", "",
              "From level hover 20 m up (rotors at hover speed; high enough that no floor is reached in 4 s: PyFlyt and Crazyflow have one), every simulator gets the same per-rotor thrust "
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
    return lines


def explanation(results, table):
    """The commentary: why the dynamics differ (only when they were measured) and what is not done."""
    import re
    (lo, hi), _, _ = open_loop_ranges(table)
    eng = re.search(r"\(MuJoCo ([^,)]+)", results.get("mjformation_version") or "")
    text = EXPLAIN.replace(
        "{open_loop_on}", "-" if lo is None else (fmt(lo, 2) if fmt(lo, 2) == fmt(hi, 2) else f"{fmt(lo, 2)}-{fmt(hi, 2)}")
    ).replace("{engine}", f"MuJoCo {eng.group(1)}" if eng else "see the version line")
    if not results["dynamics"]:
        text = text[text.index("## What is not done here"):]
    return text


def write(results, doc, out):
    """The report `doc` and its figure beside it, from one invocation's results."""
    doc = Path(doc)
    doc.parent.mkdir(parents=True, exist_ok=True)
    fig_path = doc.parent / "peers_divergence.png"
    table, curves = divergence(results)
    if curves:
        figure(curves, fig_path)
    lines = (header(results, doc) + in_short(results, table) + machine_lines(results) + vehicle_lines(results)
             + speed_lines(results) + dynamics_lines(results, table, fig_path))
    doc.write_text("\n".join(lines) + "\n" + explanation(results, table))


def section_markers(sizes):
    """The comment lines that open and close the section of these vehicle counts."""
    key = ",".join(str(n) for n in sizes)
    return (f"<!-- peers harness: speed at N = {key}, written by run_peers.py --doc-section -->",
            f"<!-- peers harness: end of speed at N = {key} -->")


def splice(text, sizes, body):
    """`text` with the section of `sizes` replaced by `body` when its markers are there, else
    with it placed before the dynamics cross-check (at the end when there is none)."""
    begin, end = section_markers(sizes)
    block = f"{begin}\n{body.rstrip()}\n{end}\n"
    if begin in text and end in text[text.index(begin):]:
        head, rest = text.split(begin, 1)
        after = rest.split(end, 1)[1]
        return head + block + (after[1:] if after.startswith("\n") else after)
    anchor = "## Dynamics cross-check"
    if anchor in text:
        head, rest = text.split(anchor, 1)
        return head + block + "\n" + anchor + rest
    return text.rstrip("\n") + "\n\n" + block


def section_provenance(results, cells):
    """When, with which command and under what load the cells were measured (the invocation
    that measured the last of them, from `invocations` when results were merged)."""
    runs = results.get("invocations") or [{"started": results["started"], "command": results["command"],
                                           "loadavg": results["machine"].get("loadavg"),
                                           "loadavg_end": results["machine"].get("loadavg_end")}]
    last = max((c.get("measured") or "" for c in cells), default="")
    inv = [r for r in runs if (r.get("started") or "") <= last][-1:] or runs[-1:]
    inv = inv[0]
    loads = ", ".join(f"{c['load'][0]:.1f}" for c in cells if c.get("load"))
    rounded = lambda xs: tuple(round(x, 2) for x in xs) if xs else "-"
    return (f"Measured from {inv.get('started')} to {inv.get('finished') or last} on the machine above "
            f"(the load average (1, 5, 15 min) was {rounded(inv.get('loadavg'))} at the start and "
            f"{rounded(inv.get('loadavg_end'))} at the end, and {loads or '-'} (1-min, one sample per cell, "
            f"in the table's order): {load_meaning(inv, cells, results['machine'].get('nproc'))}), with:"
            f"\n\n```bash\n/usr/bin/python3 {checkout_command(inv.get('command') or '')}\n```")


def load_meaning(invocation, cells, cores):
    """What the 1-min load averages around and during the cells say of the wall times: with fewer
    runnable processes than cores (about one: the measured run itself) the machine was otherwise
    idle; with more, other work took turns on the cores and every wall time is longer."""
    samples = [c["load"][0] for c in cells if c.get("load")]
    samples += [x[0] for x in (invocation.get("loadavg"), invocation.get("loadavg_end")) if x]
    cores = cores or 2
    if samples and max(samples) < cores - 0.5:
        return (f"below {cores - 0.5:g} throughout on {cores} cores, so the machine was otherwise idle "
                f"and the measured run had a core of its own")
    return (f"{cores} cores shared with other work, which was running: more runnable work than cores, "
            f"so every wall time here is longer than on an idle machine")


def section(results, sizes):
    """The Markdown section of the speed cells at `sizes` alone (--doc-section)."""
    cells = [c for c in results["speed"] if c["n"] in sizes]
    label = ", ".join(str(n) for n in sizes)
    if not cells:
        return f"## Speed at N = {label}\n\nNot measured: results.json has no cell at N = {label}.\n"
    durations = sorted({c.get("duration", results["args"]["duration"]) for c in cells})
    measured = sorted({NAMES[c["sim"]] for c in cells}, key=list(NAMES.values()).index)
    missing = [NAMES[p] for p in ("rotorpy", "pyflyt", "crazyflow") if NAMES[p] not in measured]
    ratios_text = summary({"speed": cells})
    lines = [f"## Speed at N = {label}", "",
             section_provenance(results, cells), "",
             f"Simulated seconds asked for per run: {', '.join(fmt(d, 3) for d in durations)} ("
             + ("the 40 s of the table above" if durations == [40.0] else
                "not the 40 s of the table above, so that a cell costs minutes, not hours") +
             "; a peer run still stops at "
             f"{fmt(results['args']['wall_budget'], 3)} s of wall time, \"budget\"). Runs shorter than 25 s give "
             "their error at their last time. Simulators measured: " + ", ".join(measured) + "; not run at this "
             "size: " + (", ".join(missing) or "none") + " (see \"What is not done here\").", "",
             speed_section(results, sizes), ""]
    for n in sorted({c["n"] for c in cells if c["workload"] == "W2" and c["n"] > 1}):
        radius, start = W.shape_radius(n - 1), float(np.linalg.norm(W.starts(n)[1, :2]))
        lines[-2:-2] = [f"W2 at N = {n}: the slots lie on a circle of {fmt(radius, 3)} m around the leader turning at "
                        f"{fmt(W.shape_omega(n - 1), 3)} rad/s ({fmt(radius * W.shape_omega(n - 1), 3)} m/s relative to it; neighbouring slots "
                        f"0.2 m apart) and the followers start on a ring of {fmt(start, 3)} m: whether a run "
                        "flew the work is in the error column.", ""]
    warm = max((c.get("warmup_periods", 1) for c in cells if c["sim"] != "mjformation"), default=1)
    if warm > 1:
        lines[-2:-2] = [f"The peers' first {warm} control periods are timed apart from the stepping (\"setup + "
                        "first period\" column): Crazyflow compiles its step again in its second period, which a "
                        "run with the default of one period counts in its wall time.", ""]
    if ratios_text:
        lines += [ratios_text, ""]
    return "\n".join(lines)


def write_section(results, doc, sizes):
    """The section of `sizes` spliced into the report `doc` (created when missing), the rest of
    the file left as it is."""
    doc = Path(doc)
    doc.parent.mkdir(parents=True, exist_ok=True)
    text = doc.read_text() if doc.exists() else ""
    doc.write_text(splice(text, sizes, section(results, sizes)))


EXPLAIN = """
## What the differences come from

**(a) Accelerations.** With the matched parameters, the four simulators compute the same rigid body
under the same thrusts: level and at rest they agree to rounding (Crazyflow to float32's 1e-6 relative,
JAX's default precision; the 8e-9 rad/s^2 in yaw against RotorPy and PyFlyt is mjformation's side: the
generated MJCF writes the yaw arm k_m / k_eta to 9 significant digits).
In the tilted, moving state each peer adds terms of its own model that mjformation's vehicle does not
have (MuJoCo computes no aerodynamics for it), and the "predicted" column evaluates exactly those terms
from the peers' published formulas and coefficients (peers/peerlib/crosscheck.py): the residual after
subtracting them is at rounding level, so every difference is accounted for.
- **RotorPy**: rotor drag ("H-force", `aero=True`), H_i = -w_i diag(k_d, k_d, k_z) (v_body + w x r_i) at each
  hub: a force against the body velocity of about w_hover k_d per rotor (4 x 1789 x 1.03e-6 = 7.3e-3 N per
  m/s, 0.25 m/s^2 per m/s on 30 g) and a moment from the hub offsets.
- **PyFlyt**: quadratic body drag 0.5 rho Cd A v^2 (small at these speeds: Cd A = 1.2e-3 m^2) and a
  rotational damping -1e-4 w|w| N m per body axis, which is large for a body of 1.4e-5 kg m^2: -1.75
  rad/s^2 about x at 0.5 rad/s. Bullet's rigid-body step includes the w x Jw term as MuJoCo does.
- **Crazyflow**: linear drag (its drag_matrix: -0.015 N s/m, 0.5 1/s on 30 g) and the propellers'
  gyroscopic torque (w_y h, -w_x h, 0), h = I_p sum(s_i w_i): with unequal rotor speeds the rotors' net
  angular momentum is not zero and tilts the angular acceleration by about 0.15 rad/s^2 here.
With these terms off ("drag/gyro off"), each peer agrees with mjformation to rounding in both states.
So the tolerance the models' documented differences allow is: equality to rounding without the extra
terms, and the predicted terms' size with them (here up to 0.6 m/s^2 and 2.1 rad/s^2 at 1.2 m/s and
0.7 rad/s).

**(b) Open loop.** A hovering quadrotor is open-loop unstable: a small torque error tilts it, the tilt
turns the thrust sideways and the position error grows as the second integral of the tilt, so any
difference between two simulators grows in time and the time to 5 cm measures how early the models
part. As modelled, the peers part from mjformation (and from each other) after {open_loop_on} s: their drag
terms act from the first instant the vehicle turns or moves (PyFlyt's rotational damping most, since it
acts on the attitude, whose error is integrated twice into position). With the extra terms off, what is
left is the integration of the same equations, and the table and figure show it is small:
- RotorPy (RK45 within each 10 ms step) and mjformation (semi-implicit Euler at 1 ms) integrate the same
  smooth equations finely and stay about a centimetre apart after 4 s of tumbling.
- PyFlyt (Bullet at 240 Hz, the motor state by explicit Euler at 4.17 ms) ends a few centimetres away.
- Crazyflow (explicit Euler at 500 Hz for body and motors, in float32) is the first to part, after a few
  seconds: explicit Euler's first-order error at a step twice mjformation's, the motor Euler that shortens
  the effective time constant (see (c)), and float32, which rounds the state at 1e-7 relative every step;
  this harness does not separate the three.
So the matched models agree in open loop for seconds; what separates them within about a second is the
peers' aerodynamic terms, not the integrators.

**(c) Motor lag.** All four use the matched first-order constant tau = 72 ms, but not on the same
quantity. mjformation's MuJoCo `filter` actuator lags the thrust itself, so the thrust reaches 63.2 % of
its step at tau (71.0 ms: explicit Euler at dt = 1 ms gives dt ln(0.368) / ln(1 - dt/tau) = 71.5 ms; the
measurement interpolates between 1 ms samples). RotorPy, PyFlyt (its throttle is the rotor speed as a
fraction of the maximum) and Crazyflow lag the rotor speed, and thrust goes as its square: a 1.3 x thrust
step is a 1.14 x speed step, and the thrust's 63.2 % point comes later, at 1.035 tau = 74.5 ms (RotorPy,
integrated accurately by RK45). PyFlyt and Crazyflow step the speed with explicit Euler at 4.17 ms and
2 ms, whose discrete pole (1 - dt/tau per step) is faster than exp(-dt/tau), which brings them back to
72.4 and 73.5 ms. For small commands (the open-loop test's 0.1 %) thrust lag and speed lag are the same to
first order; for large steps mjformation's thrust responds up to about 3 ms sooner.

## What is not done here, and why
- RotorPy batched: the lock pins RotorPy 3.0.0, whose README reports batched runs of more than 1000
  drones on the CPU (`BatchedMultirotor`, `simulate_batch`). That mode is the `rotorpy[batched]` extra
  (torch >= 1.11, torchdiffeq, roma, opt-einsum), none of which the lock holds, and it flies batched
  classes of its own (vehicle, controller, trajectory) that the harness's worker does not drive: not
  measured at any size. Crazyflow's batch of worlds is measured on one size (8 worlds).
- N = 1000: Crazyflow and mjformation only, in shorter runs than 40 s (the section "Speed at N = 1000"
  that `--sizes 1000 --doc-section` writes says how long, when and under what load). RotorPy and PyFlyt
  step vehicles one by one in Python: at their N = 49 vehicle-steps per second one simulated second of
  1000 vehicles costs RotorPy minutes (100 Hz) and PyFlyt tens of seconds (240 Hz), so a 30-s wall
  budget leaves them a second of flight or less; not attempted. mjformation flies 1000 followers with
  `rotor_model = "wrench"` and no contacts (its `--mjf-set`): the actuator rotor path is quadratic in
  the swarm (docs/PERFORMANCE.md).
- The runner's figures are taken on the engine the timed build links: {engine} (the version line above).
"""

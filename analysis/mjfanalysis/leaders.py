# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Report section "Non-cooperative leader": the protocols against maneuvering leaders
of unknown bounded acceleration, and sigma_f against the sample period T.

Inputs (written by scripts/leader_study.sh):
  RESULTS/leaders/<base>_<leader>[_s<seed>][_pointmass]/   run directories
  RESULTS/period_sweep/<vehicle>_<leader>/sweep.csv + run directories (mjformation sweep)
  RESULTS/leaders/theory_curves.txt                        leader_theory_test's printed curves
Every number here is recomputed from timeseries.csv / summary.json, never assumed.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import metrics as M
from . import plots
from .io import Run, axis_value, find_runs, load_sweep

PROTOCOLS = {
    "exp1_exponential": "smc_continuous (corrected: switching, exponential)",
    "exp2": "smc_discrete, T = 0.05 s",
    "exp3": "smc_discrete, T = 0.2 s",
    "consensus_baseline": "consensus_linear",
}
LEADERS = ("random_accel", "bang_bang", "lemniscate", "waypoints", "trajectory")
NAME_RE = re.compile(r"^(" + "|".join(PROTOCOLS) + r")_(" + "|".join(LEADERS)
                     + r")(?:_s(\d+))?(_pointmass)?$")
FORMATION_TOLERANCE_M = 1.0  # as the main report: "reached" = max final slot error below 1 m
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262}
NAN = float("nan")


def mean_ci(values) -> tuple[float, float]:
    """Mean and half-width of the 95 % Student-t confidence interval (NaN for one value)."""
    v = np.asarray([x for x in values if math.isfinite(x)], dtype=float)
    if len(v) == 0:
        return NAN, NAN
    if len(v) == 1:
        return float(v[0]), NAN
    return float(v.mean()), T95.get(len(v) - 1, 1.96) * float(v.std(ddof=1)) / math.sqrt(len(v))


@dataclass
class SlidingStats:
    reaching_time: float = NAN  # s: the runner's (after it every |s_i| stays in reaching_band)
    max_window: float = NAN     # max |s_i| over followers, axes and the metric window (m/s)
    ratio: float = NAN          # max_window / Delta, Delta the largest band (plugin's report)
    ratio_own: float = NAN      # max over followers of max |s_i| / Delta_i (own band each)


def follower_bands(run: Run) -> dict | None:
    """Theorem 2's Delta_i per follower (eqs. (49)-(50)), transcribed here from the run's
    config.toml (not the plugin's report, which gives only the largest):
    Delta_i = max((eps T + a_i0 k2 T (u_max - u_min) + eta0) / (2 - qT),
                  eps T + a_i0 k2 T (u_max - u_min)). None unless the protocol is discrete."""
    if not plots._is_discrete(run) or not run.config:
        return None
    f = run.config.get("formation") or {}
    topo = run.config.get("topology") or {}
    k2 = float((f.get("k") or [3.0, 1.0])[1])
    eps, q = float(f.get("eps", 0.05)), float(f.get("q", 4.5))
    T, eta0 = float(f.get("period", 0.05)), float(f.get("eta0", 1e-6))
    span = float(f.get("u_max", 1.0)) - float(f.get("u_min", -1.0))
    links = topo.get("leader_links") or []
    weights = topo.get("leader_weights") or [1.0] * len(links)
    a0 = {int(i): float(w) for i, w in zip(links, weights)}
    ts = run.timeseries
    if ts is None:
        return None
    bands = {}
    for i in M.followers(ts):
        lead = a0.get(i, 0.0) * k2 * T * span
        bands[i] = max((eps * T + lead + eta0) / (2.0 - q * T), eps * T + lead)
    return bands


def sliding_stats(run: Run) -> SlidingStats:
    """|s_i| on the metric window [25, 40] s, after any reaching phase, against Theorem 2's
    band Delta (the plugin's, the largest over followers: conservative for followers without a
    leader link). A reaching time defined from the band itself would either make the ratio <= 1
    by construction (last exit, the runner's) or be fooled by s_i crossing zero during the
    transient (first entry), so the band is tested on the window instead."""
    ts = run.timeseries
    out = SlidingStats(reaching_time=run.metric("reaching_time_s"))
    if ts is None:
        return out
    mask = M.window_mask(ts["t"], M.metric_window(run.summary, run.config))
    bands = follower_bands(run)
    worst, worst_own, seen = 0.0, 0.0, False
    for i in M.followers(ts):
        for axis in ("x", "y"):
            s = ts.get(f"uav{i}_s{axis}")
            if s is None or not np.isfinite(s[mask]).any():
                continue
            seen = True
            m = float(np.nanmax(np.abs(s[mask])))
            worst = max(worst, m)
            if bands:
                worst_own = max(worst_own, m / bands[i])
    if not seen:
        return out
    delta = run.plugin_report("delta")
    out.max_window = worst
    out.ratio = worst / delta if plots._is_discrete(run) and math.isfinite(delta) else NAN
    out.ratio_own = worst_own if bands else NAN
    return out


@dataclass
class Cell:
    """One protocol x leader x vehicle: every seed's run."""
    protocol: str
    leader: str
    vehicle: str
    runs: list = field(default_factory=list)


def collect(leaders_dir: Path) -> dict:
    cells = {}
    for run in find_runs(leaders_dir):
        m = NAME_RE.match(run.name)
        if not m:
            continue
        vehicle = "pointmass" if m.group(4) else "quadrotor"
        key = (m.group(1), m.group(2), vehicle)
        cells.setdefault(key, Cell(*key)).runs.append(run)
    for c in cells.values():
        c.runs.sort(key=lambda r: r.name)
    return cells


def _fmt(x, digits=3):
    return "—" if not (isinstance(x, (int, float)) and math.isfinite(x)) else f"{x:.{digits}g}"


def _fmt_ci(mean, half):
    if not math.isfinite(mean):
        return "—"
    return f"{mean:.3g}" + (f" ± {half:.2g}" if math.isfinite(half) else "")


def leader_acc(run: Run) -> dict:
    return (run.summary or {}).get("leader_acceleration") or {}


def table(cells: dict) -> list[str]:
    L = ["| Protocol | Leader | Vehicle | Runs | Mean σ_f on [25, 40] s (± 95 % CI) | "
         "Reaching time (s) | Max \\|s_i\\| on [25, 40] s | Max \\|s_i\\|/Δ on [25, 40] s | "
         "Max \\|s_i\\|/Δ_i (own band) | Formation reached | Leader acc. outside "
         "[u_min, u_max]: time fraction, max excess (m/s²) |",
         "|---|---|---|---|---|---|---|---|---|---|---|"]
    order = {p: k for k, p in enumerate(PROTOCOLS)}
    for key in sorted(cells, key=lambda k: (k[2] != "quadrotor", LEADERS.index(k[1]),
                                            order[k[0]])):
        c = cells[key]
        complete = [r for r in c.runs if r.complete]
        sig = mean_ci([r.metric("sigma_f_mean") for r in complete])
        stats = [sliding_stats(r) for r in complete]
        reach = [s.reaching_time for s in stats]
        reach_cell = ("never" if stats and not any(math.isfinite(x) for x in reach)
                      else _fmt_ci(*mean_ci(reach)))
        if c.protocol == "consensus_baseline":
            reach_cell = "— (no s)"
        reached = sum(1 for r in complete
                      if r.metric("max_final_slot_error_m") < FORMATION_TOLERANCE_M)
        frac = [leader_acc(r).get("fraction_outside") for r in complete]
        frac = [x for x in frac if isinstance(x, (int, float))]
        excess = [leader_acc(r).get("max_excess") for r in complete]
        excess = [x for x in excess if isinstance(x, (int, float))]
        acc_cell = (f"{max(frac):.2f}, {max(excess):+.3f}" if frac and excess else "—")
        incomplete = len(c.runs) - len(complete)
        runs_cell = f"{len(complete)}" + (f" (+{incomplete} incomplete)" if incomplete else "")
        L.append("| " + " | ".join([
            PROTOCOLS[c.protocol], c.leader, c.vehicle, runs_cell, _fmt_ci(*sig), reach_cell,
            _fmt(max((s.max_window for s in stats), default=NAN)),
            _fmt(max((s.ratio for s in stats), default=NAN)),
            _fmt(max((s.ratio_own for s in stats), default=NAN)),
            f"{reached}/{len(complete)}", acc_cell]) + " |")
    return L


def compact_table(cells: dict) -> list[str]:
    """One row per leader and protocol, both vehicles side by side."""
    L = ["| Leader | Protocol | quadrotor: mean σ_f | point mass: mean σ_f | point mass: max "
         "\\|s_i\\|/Δ, /Δ_i on [25, 40] s | reached (quad / pm) |",
         "|---|---|---|---|---|---|"]

    def sigma(c):
        return _fmt_ci(*mean_ci([r.metric("sigma_f_mean") for r in c.runs if r.complete]))

    def reached(c):
        ok = sum(1 for r in c.runs
                 if r.complete and r.metric("max_final_slot_error_m") < FORMATION_TOLERANCE_M)
        return f"{ok}/{len(c.runs)}"

    for leader in LEADERS:
        for p in PROTOCOLS:
            q, m = cells.get((p, leader, "quadrotor")), cells.get((p, leader, "pointmass"))
            if not q or not m:
                continue
            stats = [sliding_stats(r) for r in m.runs if r.complete]
            ratio = _fmt(max((s.ratio for s in stats), default=NAN))
            own = _fmt(max((s.ratio_own for s in stats), default=NAN))
            L.append(f"| {leader} | {PROTOCOLS[p]} | {sigma(q)} | {sigma(m)} | {ratio}, {own} | "
                     f"{reached(q)} / {reached(m)} |")
    return L


def fig_sigma_by_protocol(cells: dict, leader: str, vehicle: str, out_path: Path) -> Path:
    """sigma_f(t) of every protocol against one leader (first seed), log scale."""
    with plots.plt.rc_context(plots.STYLE):
        fig, ax = plots._new((8.0, 4.4))
        for k, protocol in enumerate(PROTOCOLS):
            c = cells.get((protocol, leader, vehicle))
            if not c or not c.runs or c.runs[0].timeseries is None:
                continue
            t, s = plots.sigma_f_series(c.runs[0])
            ax.plot(t, s, lw=1.0, color=f"C{k}", label=PROTOCOLS[protocol])
        ax.axvspan(25, 40, color="gold", alpha=0.2, label="window [25, 40] s")
        ax.set_yscale("log")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("σ_f (eq. (68))")
        ax.set_title(f"σ_f(t) against the {leader} leader [{vehicle}]", fontsize=9)
        ax.legend(loc="upper right")
        return plots.save_figure(fig, out_path)


def fig_sliding_window(run: Run, out_path: Path, follower: int = 1) -> Path:
    """s_1(k) on [20, 40] s with the band ±Delta: zoomed so the band is visible (the reaching
    phase, 100x larger, would flatten it)."""
    ts = run.timeseries
    delta = run.plugin_report("delta")
    with plots.plt.rc_context(plots.STYLE):
        fig, ax = plots._new((8.0, 4.2))
        if ts is not None and f"uav{follower}_sx" in ts:
            t = ts["t"]
            sel = t >= 20.0
            top = 0.0
            for axis in ("x", "y"):
                s = ts[f"uav{follower}_s{axis}"][sel]
                ax.plot(t[sel], s, lw=0.9, drawstyle="steps-post", label=f"s_{follower},{axis}")
                top = max(top, float(np.nanmax(np.abs(s))) if np.isfinite(s).any() else 0.0)
            if math.isfinite(delta):
                ax.axhspan(-delta, delta, color="gray", alpha=0.25,
                           label=f"Theorem 2 band ±Δ, Δ = {delta:.3g}")
                top = max(top, 1.5 * delta)
            ax.set_ylim(-1.1 * top, 1.1 * top)
        ax.axhline(0.0, color="black", lw=0.6)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("s (m/s)")
        ax.set_title(f"{run.name} [{run.vehicle_model}]: s_{follower} on [20, 40] s", fontsize=9)
        ax.legend(loc="upper right", fontsize=7)
        return plots.save_figure(fig, out_path)


# --- sigma_f against T ------------------------------------------------------------------------

@dataclass
class PeriodPoint:
    period: float
    sigma: list
    delta: float
    bound47: float
    rederived: float


def read_period_sweep(sweep_dir: Path) -> list[PeriodPoint]:
    """Points of one `mjformation sweep` over formation.period (and maybe leader.seed)."""
    by_t = {}
    sweep = load_sweep(sweep_dir)
    for entry in sweep.runs:
        if not entry.get("complete"):
            continue
        T = float(axis_value(entry["formation.period"]))
        run = sweep.run(entry)
        p = by_t.setdefault(T, PeriodPoint(T, [], run.plugin_report("delta"),
                                           run.plugin_report("error_bound"),
                                           run.plugin_report("error_bound_rederived")))
        p.sigma.append(run.metric("sigma_f_mean"))
    return [by_t[T] for T in sorted(by_t)]


def fitted_slope(points: list[PeriodPoint]) -> tuple[float, float]:
    """Least-squares slope of log(mean sigma_f) on log(T) and its 95 % CI half-width."""
    x = np.log([p.period for p in points])
    y = np.log([np.mean(p.sigma) for p in points])
    if len(x) < 3:
        return NAN, NAN
    A = np.vstack([x, np.ones_like(x)]).T
    coef, res, *_ = np.linalg.lstsq(A, y, rcond=None)
    dof = len(x) - 2
    s2 = float(res[0]) / dof if len(res) else 0.0
    se = math.sqrt(s2 / float(((x - x.mean()) ** 2).sum()))
    return float(coef[0]), T95.get(dof, 1.96) * se


def fig_period(sweeps: dict, out_path: Path) -> Path:
    """Mean sigma_f against T on log-log axes with Delta(T), bound (47) and the re-derived
    bound, one panel per vehicle."""
    vehicles = sorted({v for v, _ in sweeps}, key=lambda v: v != "pointmass")
    with plots.plt.rc_context(plots.STYLE):
        fig, axes = plots.plt.subplots(1, len(vehicles), figsize=(6.0 * len(vehicles), 4.8),
                                       layout="constrained", squeeze=False)
        for ax, vehicle in zip(axes[0], vehicles):
            bounds_drawn = False
            for k, ((v, leader), pts) in enumerate(sorted(sweeps.items())):
                if v != vehicle or not pts:
                    continue
                T = np.array([p.period for p in pts])
                mean = np.array([np.mean(p.sigma) for p in pts])
                ci = np.array([mean_ci(p.sigma)[1] for p in pts])
                slope, half = fitted_slope(pts)
                ax.errorbar(T, mean, yerr=np.where(np.isfinite(ci), ci, 0.0), fmt="o-", ms=4,
                            color=f"C{k}", capsize=2,
                            label=f"mean σ_f, {leader} leader (slope {slope:.2f} ± {half:.2f})")
                if not bounds_drawn:
                    ax.plot(T, [p.delta for p in pts], "k--", lw=1, label="Δ(T), eq. (49)-(50)")
                    ax.plot(T, [p.bound47 for p in pts], "k:", lw=1.2, label="bound (47)")
                    ax.plot(T, [p.rederived for p in pts], "k-.", lw=1,
                            label="re-derived bound (model (40))")
                    bounds_drawn = True
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("sample period T (s)")
            ax.set_ylabel("mean σ_f on [25, 40] s")
            ax.set_title(f"σ_f against T, smc_discrete [{vehicle}]", fontsize=9)
            ax.legend(loc="upper left", fontsize=7)
        return plots.save_figure(fig, out_path)


def period_table(sweeps: dict) -> list[str]:
    L = ["| Vehicle | Leader | T (s) | Runs | Mean σ_f (± 95 % CI) | Δ(T) | Bound (47) | "
         "Re-derived bound | Below (47) | Below re-derived |", "|---|---|---|---|---|---|---|---|---|---|"]
    for (vehicle, leader), pts in sorted(sweeps.items()):
        for p in pts:
            m, h = mean_ci(p.sigma)
            L.append(f"| {vehicle} | {leader} | {p.period:g} | {len(p.sigma)} | {_fmt_ci(m, h)} "
                     f"| {_fmt(p.delta)} | {_fmt(p.bound47)} | {_fmt(p.rederived)} | "
                     f"{'yes' if max(p.sigma) <= p.bound47 else '**no**'} | "
                     f"{'yes' if max(p.sigma) <= p.rederived else '**no**'} |")
    return L


# --- theory curves (leader_theory_test output) -----------------------------------------------

def read_theory_curves(path: Path) -> dict:
    """{curve number: [(T, x, measured, bound)]} from the test's '[ info ]' lines."""
    curves, current = {}, None
    for line in path.read_text().splitlines():
        m = re.search(r"curve (\d)", line)
        if m:
            current = int(m.group(1))
            curves[current] = []
            continue
        m = re.match(r"\[ info \]\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s*$", line)
        if m and current:
            curves[current].append(tuple(float(g) for g in m.groups()))
    return curves


def fig_theory_curves(curves: dict, out_path: Path) -> Path:
    titles = {1: ("leader at ±r u_max, declared [-1, 1]", "r = |u_0| / u_max"),
              2: ("leader at ±1, declared [-d, d]", "violation 1 / d")}
    with plots.plt.rc_context(plots.STYLE):
        fig, axes = plots.plt.subplots(1, 2, figsize=(11, 4.4), layout="constrained")
        for ax, n in zip(axes, (1, 2)):
            rows = curves.get(n, [])
            for k, T in enumerate(sorted({r[0] for r in rows})):
                sel = [r for r in rows if r[0] == T]
                x = [r[1] if n == 1 else 1.0 / r[1] for r in sel]
                ax.plot(x, [r[2] for r in sel], "o-", color=f"C{k}", label=f"measured, T = {T:g}")
                ax.plot(x, [r[3] for r in sel], "--", color=f"C{k}", lw=1,
                        label=f"invariant bound L/Δ, T = {T:g}")
            ax.axhline(1.0, color="gray", lw=0.8)
            ax.set_yscale("log")
            ax.set_xlabel(titles[n][1])
            ax.set_ylabel("max |s_1| / Δ after reaching")
            ax.set_title(f"bang_bang {titles[n][0]}: model (40), 12 seeds", fontsize=9)
            ax.legend(fontsize=7)
        return plots.save_figure(fig, out_path)


# --- the section ------------------------------------------------------------------------------

def _rel(path: Path, start: Path) -> str:
    import os
    return os.path.relpath(path, start)


def section(results_dir: Path, out_dir: Path) -> list[str]:
    """Markdown lines of the section; empty when the study has not been run."""
    results_dir, out_dir = Path(results_dir), Path(out_dir)
    leaders_dir, sweep_dir = results_dir / "leaders", results_dir / "period_sweep"
    if not leaders_dir.is_dir() and not sweep_dir.is_dir():
        return []
    fig_dir = out_dir / "figures" / "leaders"
    L = ["## Non-cooperative leader", ""]
    L.append("The leader's acceleration u_0 is unknown to the followers, only bounded: "
             "u_min ≤ u_0 ≤ u_max per axis (Assumption 1, Remark 1). Five guidance plugins fly "
             "it: `random_accel` (smooth seeded random acceleration filling [-1, 1] m/s²), "
             "`bang_bang` (±1 m/s² per axis, switching after random dwell times), `lemniscate`, "
             "`waypoints` and `trajectory` (a recorded path). Their commands stay inside "
             "[-1, 1]; the leader's *measured* acceleration (finite difference of MuJoCo's "
             "velocity sensor) is what the last column reports. Regenerate with "
             "`bash scripts/leader_study.sh` (runs and this section).")
    L.append("")
    cells = collect(leaders_dir) if leaders_dir.is_dir() else {}
    if cells:
        L.extend(_protocol_lines(cells, fig_dir, out_dir))
    L.extend(_theory_lines(leaders_dir, fig_dir, out_dir))
    if sweep_dir.is_dir():
        L.extend(_period_lines(sweep_dir, fig_dir, out_dir))
    return L


def _protocol_lines(cells, fig_dir: Path, out_dir: Path) -> list[str]:
    """The per-leader, per-protocol tables and figures."""
    L = []
    L.append("### Per leader and protocol")
    L.append("")
    L.append("Seeded leaders (`random_accel`, `bang_bang`) run with seeds 1-5: mean ± "
             "95 % Student-t CI over seeds; the others are deterministic (one run). "
             "Reaching time: the runner's (`reaching_time_s`: from then on every |s_i| "
             "stays inside its `reaching_band`: Δ for the discrete protocol, 0.1 for the "
             "others, widened to the smallest Δ 2^k that holds |s| over the metric window "
             "when that is at most a tenth of the largest |s|; 'never' when it does not). The band is tested on the window [25, 40] s, long after any "
             "reaching phase: max |s_i| there over every follower and axis, and its ratio "
             "to Δ (the plugin's, the largest over followers) and to each follower's own "
             "Δ_i (eqs. (49)-(50) recomputed from config.toml: followers without a leader "
             "link have Δ_i = εT only). A reaching time defined from "
             "the band itself would make 'after reaching' ≤ Δ by construction (last exit) "
             "or be fooled by s_i crossing zero during the transient (first entry). "
             f"Formation reached: max final slot error < {FORMATION_TOLERANCE_M:g} m. "
             "Leader acceleration: measured; max excess < 0 means inside the bounds by "
             "that margin.")
    L.append("")
    L.extend(compact_table(cells))
    L.append("")
    L.append("In detail (reaching time, |s_i| on the window, the leader's measured "
             "acceleration):")
    L.append("")
    L.extend(table(cells))
    L.append("")
    for vehicle in ("quadrotor", "pointmass"):
        for leader in LEADERS:
            if not any(k[1] == leader and k[2] == vehicle for k in cells):
                continue
            L.append(f"#### {leader} leader, {vehicle}")
            L.append("")
            p = fig_sigma_by_protocol(cells, leader, vehicle,
                                      fig_dir / f"sigma_f_{leader}_{vehicle}.png")
            L.append(f"![sigma_f, {leader}, {vehicle}]({_rel(p, out_dir)})")
            L.append("")
            c = cells.get(("exp2", leader, vehicle))
            if c and c.runs:
                run = c.runs[0]
                if vehicle == "quadrotor":
                    p = plots.fig_trajectories(run, fig_dir / run.name / "trajectories_xy.png")
                    L.append(f"![trajectories {run.name}]({_rel(p, out_dir)})")
                    L.append("")
                p = fig_sliding_window(run, fig_dir / run.name / "sliding_s1_window.png")
                L.append(f"![s_1 with ±Δ, {run.name}]({_rel(p, out_dir)})")
                L.append("")
    return L


def _theory_lines(leaders_dir: Path, fig_dir: Path, out_dir: Path) -> list[str]:
    """The leader-outside-the-bounds curves, when leader_theory_test wrote them."""
    L = []
    curves_file = leaders_dir / "theory_curves.txt"
    if curves_file.is_file():
        curves = read_theory_curves(curves_file)
        if curves:
            L.append("### Leader outside the bounds, bounds declared too small (model (40))")
            L.append("")
            L.append("From `leader_theory_test` (CurvesLeaderOutsideTheBoundsAndMisdeclaredBounds)"
                     ": documented curves, not pass/fail. Dashed: our invariant bound "
                     "L = max(Δ, Δ2 + k2 T v, (k2 v - ε)/q) for a leader v beyond the declared "
                     "bounds (derivation in the test); (k2 v - ε)/q does not shrink with T, so "
                     "the excess ratio grows like 1/T.")
            L.append("")
            p = fig_theory_curves(curves, fig_dir / "excess_curves.png")
            L.append(f"![excess of |s| over the band]({_rel(p, out_dir)})")
            L.append("")
    return L


def _period_lines(sweep_dir: Path, fig_dir: Path, out_dir: Path) -> list[str]:
    """sigma_f against the sample period T."""
    L = []
    sweeps = {}
    for d in sorted(sweep_dir.iterdir()):
        if (d / "sweep.json").is_file():
            vehicle, _, leader = d.name.partition("_")
            sweeps[(vehicle, leader)] = read_period_sweep(d)
    if sweeps:
        L.append("### σ_f against the sample period T")
        L.append("")
        L.append("`smc_discrete` (Exp. 2's gains, q = 4.5 so 1 - qT > 0 up to 0.2 s) over "
                 "12 periods from 0.005 to 0.2 s, the paper's circle leader and the "
                 "bang_bang leader (seeds 1-5, mean ± 95 % CI). Slope: least-squares fit of "
                 "log mean σ_f on log T (± 95 % CI); Theorem 2's band is O(T).")
        L.append("")
        for (vehicle, leader), pts in sorted(sweeps.items()):
            slope, half = fitted_slope(pts)
            L.append(f"- fitted slope, {vehicle}, {leader} leader: **{_fmt(slope, 3)} ± "
                     f"{_fmt(half, 2)}** ({len(pts)} periods)")
        L.append("")
        p = fig_period(sweeps, fig_dir / "sigma_f_vs_T.png")
        L.append(f"![sigma_f against T]({_rel(p, out_dir)})")
        L.append("")
        L.extend(period_table(sweeps))
        L.append("")
    return L


def write_section(results_dir, out_dir) -> Path:
    """Writes out_dir/leaders.md alone (the study script's report)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    lines = section(Path(results_dir), out_dir)
    if not lines:
        raise FileNotFoundError(f"{results_dir}: no leaders/ or period_sweep/ folder")
    path = out_dir / "leaders.md"
    path.write_text("# mjformation: non-cooperative leaders\n\n" + "\n".join(lines).rstrip("\n")
                    + "\n")
    return path

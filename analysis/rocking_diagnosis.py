#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Why the vehicles rock: the point mass with an actuation lag tau (and an acceleration limit)
beside the quadrotor, Exps 2 and 3 (runs written by scripts/rocking_diagnosis.sh).

Usage: /usr/bin/python3 analysis/rocking_diagnosis.py OUT_DIR
Writes OUT_DIR/rocking.md (table) and OUT_DIR/rocking.png (figure).
Every run is measured the same way, from timeseries.csv, over the run's metric window (summary.json
metrics.sigma_f_window):
the followers' actual horizontal acceleration a (central differences of the recorded velocity),
as the tilt it needs, atan(|a| / g) (RMS over time and followers, deg), and the dominant
frequency of a (Hann-weighted spectrum, 0.3-5 Hz, median over followers).
"""

import math
import re
import sys
from pathlib import Path

import numpy as np
from mjfanalysis import load_run, window_label

G = 9.81
BAND = (0.3, 5.0)


def measure(path: Path) -> dict:
    run = load_run(path)
    ts = run.timeseries
    if ts is None:
        raise ValueError(f"{path}: {run.ts_error}")
    window = run.metric_window
    if window is None:
        raise ValueError(f"{path}: summary.json gives no metrics.sigma_f_window")
    t = ts["t"]
    summary = run.summary
    m = summary["metrics"]
    sel = (t >= window[0]) & (t <= window[1])
    tilts, freqs, cmd = [], [], []
    cross, power_cmd, spectra = 0, 0, []
    i = 1
    while f"uav{i}_vx" in ts:
        ax = np.gradient(ts[f"uav{i}_vx"], t)
        ay = np.gradient(ts[f"uav{i}_vy"], t)
        tilts.append(np.degrees(np.arctan(np.hypot(ax, ay)[sel] / G)))
        cmd.append(np.hypot(ts[f"uav{i}_ax_cmd"], ts[f"uav{i}_ay_cmd"])[sel])
        ts_w = t[sel]
        w = np.hanning(sel.sum())
        dt = float(np.median(np.diff(ts_w)))
        f = np.fft.rfftfreq(sel.sum(), dt)
        p = sum(np.abs(np.fft.rfft(w * (a[sel] - a[sel].mean()))) ** 2 for a in (ax, ay))
        band = (f >= BAND[0]) & (f <= BAND[1])
        freqs.append(float(f[band][np.argmax(p[band])]))
        # Command -> actual acceleration, per axis: spectra kept for the cross-spectrum below.
        for a, c in ((ax, ts[f"uav{i}_ax_cmd"]), (ay, ts[f"uav{i}_ay_cmd"])):
            spectra.append((np.fft.rfft(w * (c[sel] - c[sel].mean())),
                            np.fft.rfft(w * (a[sel] - a[sel].mean()))))
        i += 1
    # Phase of actual vs commanded acceleration at the rocking frequency (median over
    # followers), summed cross-spectrum over followers and axes, +-1 bin: the lag the formation
    # loop sees. A first-order lag tau gives atan(2 pi f tau).
    f_rock = float(np.median(freqs))
    k = int(np.argmin(np.abs(f - f_rock)))
    for c_spec, a_spec in spectra:
        cross = cross + np.sum(np.conj(c_spec[k - 1:k + 2]) * a_spec[k - 1:k + 2])
        power_cmd = power_cmd + np.sum(np.abs(c_spec[k - 1:k + 2]) ** 2)
    lag_deg = float(-np.degrees(np.angle(cross))) if power_cmd > 0 else math.nan
    gain = float(np.abs(cross) / power_cmd) if power_cmd > 0 else math.nan
    tilt = np.concatenate(tilts)
    return {
        "window": window,
        "complete": bool(summary.get("complete")),
        "t_end": float(t[-1]),
        "sigma_f_mean": m["sigma_f_mean"],
        "max_slot_error_m": m["max_final_slot_error_m"],
        "tilt_needed_rms_deg": float(np.sqrt(np.mean(tilt**2))),
        "accel_hz": float(np.median(freqs)),
        "cmd_rms": float(np.sqrt(np.mean(np.concatenate(cmd) ** 2))),
        "lag_deg": lag_deg,
        "gain": gain,
        "quad_rms_tilt_deg": (float(np.mean(m["rms_tilt_deg_in_window"]))
                              if m.get("rms_tilt_deg_in_window") and
                              all(x is not None for x in m["rms_tilt_deg_in_window"]) else math.nan),
    }


def rocking_table(results):
    """The Markdown table of every run, and the point-mass curves keyed by (exp, limit)."""
    lines = ["| exp | vehicle | lag tau (s) | accel. limit (m/s^2) | mean σ_f | max slot error (m) | "
             "RMS tilt needed atan(|a|/g) (deg) | quadrotor RMS tilt (deg) | rocking (Hz) | "
             "RMS |u| command (m/s^2) | a vs command at the rocking frequency: lag (deg), gain |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    curves = {}

    def order(item):
        (exp, name), _ = item
        pm = re.fullmatch(r"pm_tau([0-9.]+)_lim([0-9.]+)", name)
        return (exp, 0 if pm else 1, float(pm.group(2)) if pm else 0,
                float(pm.group(1)) if pm else 0, name)

    for (exp, name), r in sorted(results.items(), key=order):
        pm = re.fullmatch(r"pm_tau([0-9.]+)_lim([0-9.]+)", name)
        if pm:
            tau, lim = float(pm.group(1)), float(pm.group(2))
            vehicle = "point mass"
            curves.setdefault((exp, lim), []).append((tau, r))
        else:
            tau, lim, vehicle = math.nan, math.nan, "quadrotor " + name.replace("quad_", "")
        lines.append("| " + " | ".join([
            exp, vehicle, f"{tau:g}" if math.isfinite(tau) else "—",
            (f"{lim:g}" if lim else "none") if math.isfinite(lim) else "g tan 0.55 = 6.0 (tilt)",
            (f"{r['sigma_f_mean']:.3f}" if r["complete"] else
             f"diverged (stopped at t = {r['t_end']:.0f} s)"),
            f"{r['max_slot_error_m']:.3g}",
            f"{r['tilt_needed_rms_deg']:.1f}",
            f"{r['quad_rms_tilt_deg']:.1f}" if math.isfinite(r["quad_rms_tilt_deg"]) else "—",
            f"{r['accel_hz']:.2f}", f"{r['cmd_rms']:.2f}",
            f"{r['lag_deg']:.0f}, {r['gain']:.2f}"]) + " |")
    return lines, curves


def rocking_figure(results, curves, path: Path) -> None:
    """Tilt needed, rocking frequency and sigma_f against the lag tau, point mass and quadrotor."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    colors = {"exp2": "tab:blue", "exp3": "tab:red"}
    for (exp, lim), pts in sorted(curves.items()):
        pts.sort(key=lambda p: p[0])
        taus = [p[0] for p in pts]
        style = "-o" if lim == 0 else ("--s" if abs(lim - 6.0) < 1e-9 else ":x")
        label = (f"{exp} point mass, " + ("no limit" if lim == 0 else f"|a_x|,|a_y| <= {lim:g}")
                 + (f" (g tan {math.atan(lim / G):.2f})" if lim else ""))
        axes[0].plot(taus, [p[1]["tilt_needed_rms_deg"] for p in pts], style,
                     color=colors.get(exp), label=label)
        axes[1].plot(taus, [p[1]["accel_hz"] for p in pts], style, color=colors.get(exp))
        axes[2].semilogy(taus, [p[1]["sigma_f_mean"] for p in pts], style, color=colors.get(exp))
    for (exp, name), r in results.items():
        if not name.startswith("quad_"):
            continue
        # Lag of each plugin's small-step attitude bandwidth, 2.2 / (10-90 % rise) of the tilt step
        # (tests/plugins/attitude GeometricTest.StepResponsesOfBothPlugins): 11.4 and 7.1 rad/s.
        tau = 0.088 if "pd_cascade" in name else 0.141
        marker = "*" if "pd_cascade" in name else "P"
        kw = dict(color=colors.get(exp), marker=marker, markersize=14, linestyle="none",
                  markeredgecolor="k")
        axes[0].plot([tau], [r["tilt_needed_rms_deg"]], label=f"{exp} quadrotor {name[5:]}", **kw)
        axes[1].plot([tau], [r["accel_hz"]], **kw)
        axes[2].semilogy([tau], [r["sigma_f_mean"]], **kw)
    axes[0].set_ylabel("RMS tilt needed, atan(|a|/g) (deg)")
    axes[1].set_ylabel("dominant frequency of a (Hz)")
    windows = {r["window"] for r in results.values()}
    axes[2].set_ylabel("mean σ_f over " + (window_label(windows.pop()) if len(windows) == 1
                                           else "each run's metric window"))
    for ax in axes:
        ax.set_xlabel("actuation lag τ (s)")
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Point mass with lag τ (lines) vs quadrotor (markers, placed at the lag of its "
                 "small-step attitude bandwidth)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    out = Path(argv[0])
    results = {}
    for exp_dir in sorted(p for p in out.iterdir() if p.is_dir() and p.name.startswith("exp")):
        for run in sorted(exp_dir.iterdir()):
            if (run / "summary.json").exists():
                results[(exp_dir.name, run.name)] = measure(run)
    if not results:
        print(f"rocking_diagnosis.py: no runs in {out}", file=sys.stderr)
        return 2
    lines, curves = rocking_table(results)
    (out / "rocking.md").write_text("\n".join(lines) + "\n")
    rocking_figure(results, curves, out / "rocking.png")
    print(f"rocking_diagnosis.py: wrote {out / 'rocking.md'} and rocking.png ({len(results)} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Estimate against truth, for a run whose [estimator] is not passthrough: per
follower the horizontal position error of the estimate (x and y, m) with the filter's own
+/- 2 sigma band, and the NEES of the (p, v) estimate over time with the chi-square 95 % band
of one sample (state dimension 6).

Reads only the run's timeseries.csv (uav<i>_p{x,y}, uav<i>_p{x,y}_est, _std, uav<i>_nees: see
docs/REALISM.md, "Estimation records") and, when present, summary.json "estimation" for the
band and the window means. A run without _est columns gets no figure.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .io import Run  # noqa: E402
from .plots import STYLE, follower_color, save_figure  # noqa: E402

FIGURE_NAME = "estimation.png"
STATE_DIM = 6
Z975 = 1.959963985  # the standard normal 0.975 quantile


def chi2_quantile_wh(p_z: float, k: float) -> float:
    """The chi-square quantile of k degrees of freedom at the normal quantile p_z, by
    Wilson & Hilferty (1931): k (1 - 2/(9k) + z sqrt(2/(9k)))^3. For k = 6 it gives
    [1.206, 14.44] against the exact [1.237, 14.45]; used only when summary.json has no band."""
    v = 2.0 / (9.0 * k)
    return k * max(1.0 - v + p_z * math.sqrt(v), 0.0) ** 3


def single_band(summary: dict | None) -> tuple[float, float]:
    """The 95 % band of one NEES sample: summary.json's exact one, else Wilson-Hilferty's."""
    band = ((summary or {}).get("estimation") or {}).get("nees_band_95_single")
    if band and all(b is not None for b in band):
        return float(band[0]), float(band[1])
    return chi2_quantile_wh(-Z975, STATE_DIM), chi2_quantile_wh(Z975, STATE_DIM)


def estimated_vehicles(ts: dict) -> list[int]:
    """The vehicle indices with estimate columns, in order."""
    out, i = [], 0
    while f"uav{i}_px_est" in ts:
        out.append(i)
        i += 1
    return out


def _vehicle_stats(summary: dict | None, i: int) -> dict:
    for v in ((summary or {}).get("estimation") or {}).get("vehicles") or []:
        if v.get("vehicle") == i:
            return v
    return {}


def _fmt(x, unit="") -> str:
    return "—" if x is None or not math.isfinite(float(x)) else f"{float(x):.3g}{unit}"


def _error_panel(ax, ts: dict, t, i: int, summary: dict | None) -> None:
    """Follower i: e_x, e_y of the estimate with their +/- 2 sigma bands about zero."""
    for axis, colour in (("x", "tab:blue"), ("y", "tab:orange")):
        err = ts[f"uav{i}_p{axis}_est"] - ts[f"uav{i}_p{axis}"]
        two_sigma = 2.0 * ts[f"uav{i}_p{axis}_std"]
        ax.fill_between(t, -two_sigma, two_sigma, color=colour, alpha=0.15, lw=0)
        ax.plot(t, err, color=colour, lw=0.9, label=f"$\\hat p_{axis} - p_{axis}$")
    stats = _vehicle_stats(summary, i)
    note = ""
    if stats:
        note = (f"RMS |p̂ - p| {_fmt(stats.get('position_rms_m'), ' m')} "
                f"(relative to the leader {_fmt(stats.get('position_rms_relative_to_leader_m'), ' m')}), "
                f"|v̂ - v| {_fmt(stats.get('velocity_rms_m_s'), ' m/s')}, "
                f"mean NEES {_fmt(stats.get('nees_mean'))}; gated {_fmt(stats.get('gated'))}")
    ax.set_ylabel(f"follower {i}\n(m)")
    ax.text(0.01, 0.95, note, transform=ax.transAxes, fontsize=7, va="top")
    ax.axhline(0.0, color="black", lw=0.5)


def _nees_panel(ax, ts: dict, t, followers: list[int], summary: dict | None) -> None:
    lo, hi = single_band(summary)
    ax.axhspan(lo, hi, color="tab:green", alpha=0.12, lw=0,
               label=f"χ²({STATE_DIM}) 95 % band [{lo:.3g}, {hi:.3g}]")
    ax.axhline(STATE_DIM, color="tab:green", lw=0.8, ls="--")
    for i in followers:
        nees = ts.get(f"uav{i}_nees")
        if nees is None:
            continue
        ax.plot(t, np.where(nees > 0, nees, np.nan), color=follower_color(i), lw=0.7)
    ax.set_yscale("log")
    ax.set_ylabel("NEES of (p, v)")
    ax.set_xlabel("t (s)")
    est = (summary or {}).get("estimation") or {}
    window = est.get("window_s")
    if window:
        for w in window:
            ax.axvline(w, color="grey", lw=0.6, ls=":")
    f = est.get("followers") or {}
    if f:
        band = f.get("nees_band_95") or [None, None]
        ax.set_title(f"NEES; followers' mean in the window {_fmt(f.get('nees_mean'))} "
                     f"(95 % band for {f.get('nees_samples')} independent samples "
                     f"[{_fmt(band[0])}, {_fmt(band[1])}])", fontsize=8)
    # One line per follower, in the colours of the other figures; only the band is labelled.
    ax.legend(loc="lower right", fontsize=7, framealpha=0.85)


def figure(run: Run, out_path) -> Path | None:
    """Writes the estimate-vs-truth figure to out_path; None when the run has no estimate."""
    ts = run.timeseries
    if ts is None:
        return None
    vehicles = estimated_vehicles(ts)
    followers = [i for i in vehicles if i > 0] or vehicles
    if not followers:
        return None
    t = ts["t"]
    n = len(followers)
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(n + 1, 1, sharex=True, figsize=(7.5, 1.35 * n + 2.6),
                                 gridspec_kw={"height_ratios": [1.0] * n + [1.8]})
        for ax, i in zip(axes[:-1], followers):
            _error_panel(ax, ts, t, i, run.summary)
        plugin = ((run.summary or {}).get("estimation") or {}).get("plugin", "estimator")
        # The colours are named in the title: a legend would cover the per-follower note.
        axes[0].set_title(f"{run.name}: {plugin} estimate − truth, x (blue) and y (orange); "
                          "shaded: the filter's ±2σ", fontsize=9)
        _nees_panel(axes[-1], ts, t, followers, run.summary)
        fig.tight_layout()
        return save_figure(fig, out_path)

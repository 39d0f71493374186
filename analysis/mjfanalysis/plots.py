# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The paper's figures (section 6, Figs. 10-27) for one run, and the cross-run comparison.

Every function writes one PNG and returns its path. Output is deterministic: same data, same
bytes (Agg backend, fixed style, no PNG 'Software' metadata, fixed SVG hash salt).
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

from . import metrics as M  # noqa: E402
from .io import MARKED_EVENT_KINDS, Run, short_event  # noqa: E402

DPI = 110
STYLE = {
    "figure.figsize": (7.0, 4.6),
    "axes.grid": True,
    "grid.alpha": 0.35,
    "font.size": 10,
    "legend.fontsize": 8,
    "svg.hashsalt": "mjformation",
    "path.simplify": False,
}
LEADER_COLOR = "black"
FIGURE_NAMES = {
    "trajectories": "trajectories_xy.png",
    "final_positions": "final_positions.png",
    "pitch_roll": "attitude_pitch_roll.png",
    "yaw": "attitude_yaw.png",
    "sliding": "sliding_s1.png",
    "sigma_f": "sigma_f.png",
}


def follower_color(i: int):
    return plt.get_cmap("tab10")((i - 1) % 10)


# Safety events: pure red, used for nothing else in the figures (tests look for it).
EVENT_COLOR = (1.0, 0.0, 0.0)
MAX_EVENT_MARKS = 10  # the first ones; more would hide the curves


def marked_events(run: Run) -> list[dict]:
    """The safety events drawn in the figures: flips, impacts, collisions, region exits."""
    out = [e for e in run.events if e.get("kind") in MARKED_EVENT_KINDS
           and isinstance(e.get("time_s"), (int, float))]
    return out[:MAX_EVENT_MARKS]


def _mark_events_in_time(ax, run: Run, legend=True) -> int:
    """A labelled vertical red line at each marked event's time; returns how many."""
    events = marked_events(run)
    for k, e in enumerate(events):
        t = float(e["time_s"])
        ax.axvline(t, color=EVENT_COLOR, lw=1.3, ls="-", zorder=5,
                   label="safety event" if legend and k == 0 else None)
        ax.annotate(short_event(e), (t, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(2, -2 - 10 * (k % 4)), textcoords="offset points", ha="left",
                    va="top", fontsize=7, color=EVENT_COLOR, zorder=6,
                    bbox={"facecolor": "white", "alpha": 0.8, "lw": 0, "pad": 0.5})
    return len(events)


def _mark_events_in_plane(ax, run: Run) -> int:
    """A red cross where each marked event happened (the vehicles' recorded positions at the
    row nearest its time), labelled; returns how many."""
    ts = run.timeseries
    events = marked_events(run)
    if ts is None:
        return 0
    t = ts["t"]
    for k, e in enumerate(events):
        row = int(np.argmin(np.abs(t - float(e["time_s"]))))
        vs = [v for v in e.get("vehicles") or [] if f"uav{v}_px" in ts]
        if not vs:
            continue
        x = float(np.mean([ts[f"uav{v}_px"][row] for v in vs]))
        y = float(np.mean([ts[f"uav{v}_py"][row] for v in vs]))
        ax.plot(x, y, "X", ms=11, color=EVENT_COLOR, mec="white", mew=0.8, zorder=6,
                label="safety event" if k == 0 else None)
        ax.annotate(short_event(e), (x, y), textcoords="offset points", xytext=(6, 6),
                    fontsize=7, color=EVENT_COLOR, zorder=6)
    return len(events)


def save_figure(fig, out_path) -> Path:
    """Writes the figure (its folder made, no Software tag so the bytes repeat) and closes it."""
    out_path = Path(out_path)
    out_path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out_path, dpi=DPI, metadata={"Software": None})
    plt.close(fig)
    return out_path


def _title(run: Run, what: str, fig_index: int) -> str:
    exp = M.paper_experiment(run.summary, run.name)
    ref = f" (cf. paper Fig. {M.PAPER_FIGURES[exp][fig_index]})" if exp else ""
    head = f"{run.label} [{run.vehicle_model}]"
    if exp:
        head = f"Exp. {exp}, {head}"
    tail = "" if run.complete else f"  — {run.status.upper()}"
    if run.event_count:
        n = run.event_count
        tail += f"  — {n} SAFETY EVENT{'S' if n > 1 else ''}"
    return f"{head}{tail}\n{what}{ref}"


def _new(figsize=None):
    with plt.rc_context(STYLE):
        fig, ax = plt.subplots(figsize=figsize or STYLE["figure.figsize"], layout="constrained")
    return fig, ax


def _no_data(run: Run, out_path, what: str, fig_index: int, why: str) -> Path:
    with plt.rc_context(STYLE):
        fig, ax = _new()
        ax.set_title(_title(run, what, fig_index), fontsize=9)
        ax.text(0.5, 0.5, why, ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        return save_figure(fig, out_path)


def _rows(run: Run):
    ts = run.timeseries
    if ts is None:
        return None
    return ts


def fig_trajectories(run: Run, out_path) -> Path:
    """X-Y trajectories of all vehicles over the run; start = circle, end = square (Figs. 10,
    16, 22)."""
    what = "X-Y trajectories"
    ts = _rows(run)
    if ts is None:
        return _no_data(run, out_path, what, 0, run.ts_error or "no data")
    t = ts["t"]
    with plt.rc_context(STYLE):
        fig, ax = _new((6.6, 6.2))
        for i in M.vehicle_ids(ts):
            x, y = ts[f"uav{i}_px"], ts[f"uav{i}_py"]
            leader = i == 0
            c = LEADER_COLOR if leader else follower_color(i)
            ax.plot(x, y, color=c, lw=2.0 if leader else 1.1, ls="--" if leader else "-",
                    label="leader" if leader else f"follower {i}", zorder=3 if leader else 2)
            ax.plot(x[0], y[0], "o", ms=7, mfc="white", mec=c, mew=1.5, zorder=4)
            ax.plot(x[-1], y[-1], "s", ms=7, color=c, zorder=4)
        _mark_events_in_plane(ax, run)
        ax.plot([], [], "o", mfc="white", mec="gray", label=f"start, t = {t[0]:g} s")
        ax.plot([], [], "s", color="gray", label=f"end, t = {t[-1]:g} s")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("X (m)")
        ax.set_ylabel("Y (m)")
        ax.set_title(_title(run, f"{what}, t = {t[0]:g}..{t[-1]:g} s", 0), fontsize=9)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
        return save_figure(fig, out_path)


def formation_radius(run: Run) -> float:
    p = M.shape_parameters(run.summary, run.config)
    if p["radius"] is not None and (p["type"] in (None, "circle")):
        return p["radius"]
    ts = run.timeseries
    return M.slot_radius(ts) if ts is not None else float("nan")


def fig_final_positions(run: Run, out_path) -> Path:
    """Positions at the final time, the desired circle about the leader, the slots (Figs. 11,
    17, 23)."""
    what = "positions at the final time"
    ts = _rows(run)
    if ts is None:
        return _no_data(run, out_path, what, 1, run.ts_error or "no data")
    t_end = ts["t"][-1]
    r = formation_radius(run)
    lx, ly = ts["uav0_px"][-1], ts["uav0_py"][-1]
    with plt.rc_context(STYLE):
        fig, ax = _new((6.6, 6.2))
        if math.isfinite(r):
            ax.add_patch(Circle((lx, ly), r, fill=False, color="red", lw=1.5,
                                label=f"desired circle, r = {r:g} m"))
        ax.plot(lx, ly, "*", ms=16, color=LEADER_COLOR, label="leader", zorder=4)
        for k, i in enumerate(M.followers(ts)):
            c = follower_color(i)
            px, py = ts[f"uav{i}_px"][-1], ts[f"uav{i}_py"][-1]
            sx, sy = ts[f"uav{i}_slot_x"][-1], ts[f"uav{i}_slot_y"][-1]
            ax.plot([sx, px], [sy, py], color=c, lw=0.8, ls=":")
            ax.plot(sx, sy, "x", ms=9, mew=1.8, color="black", zorder=5)
            ax.plot(px, py, "s", ms=9, color=c, alpha=0.85, label=f"follower {i}", zorder=4)
            ax.annotate(str(i), (px, py), textcoords="offset points", xytext=(6, 6), fontsize=8)
        ax.plot([], [], "x", ms=9, mew=1.8, color="black", label="slot = leader + f_ip")
        ax.set_aspect("equal", adjustable="datalim")
        # Frame the circle and every follower (a diverged follower must stay visible).
        xs = [lx] + [ts[f"uav{i}_{c}"][-1] for i in M.followers(ts) for c in ("px", "slot_x")]
        ys = [ly] + [ts[f"uav{i}_{c}"][-1] for i in M.followers(ts) for c in ("py", "slot_y")]
        if math.isfinite(r):
            xs += [lx - 1.3 * r, lx + 1.3 * r]
            ys += [ly - 1.3 * r, ly + 1.3 * r]
        xs = [v for v in xs if math.isfinite(v)]
        ys = [v for v in ys if math.isfinite(v)]
        if xs and ys:
            pad = 0.08 * max(max(xs) - min(xs), max(ys) - min(ys), 1.0)
            ax.set_xlim(min(xs) - pad, max(xs) + pad)
            ax.set_ylim(min(ys) - pad, max(ys) + pad)
        err = M.final_slot_errors(ts)
        ax.text(0.02, 0.02, f"max |p_i - slot_i| = {np.nanmax(err):.3g} m" if err.size else "",
                transform=ax.transAxes, fontsize=8,
                bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        ax.set_xlabel("X (m)")
        ax.set_ylabel("Y (m)")
        ax.set_title(_title(run, f"{what} t = {t_end:g} s", 1), fontsize=9)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
        return save_figure(fig, out_path)


def _angles_deg(ts, i, name):
    return np.degrees(ts[f"uav{i}_{name}"])


def fig_pitch_roll(run: Run, out_path, follower: int = 1) -> Path:
    """Pitch and roll of follower 1 vs time, degrees (Figs. 12, 18, 24)."""
    what = f"pitch and roll of follower {follower}"
    ts = _rows(run)
    if ts is None or f"uav{follower}_pitch" not in ts:
        return _no_data(run, out_path, what, 2, run.ts_error or f"no follower {follower}")
    t = ts["t"]
    with plt.rc_context(STYLE):
        fig, ax = _new()
        ax.plot(t, _angles_deg(ts, follower, "pitch"), lw=1.0, label="pitch θ")
        ax.plot(t, _angles_deg(ts, follower, "roll"), lw=1.0, label="roll φ")
        _mark_events_in_time(ax, run)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("angle (deg)")
        ax.set_title(_title(run, what, 2), fontsize=9)
        ax.legend(loc="best")
        return save_figure(fig, out_path)


def fig_yaw(run: Run, out_path, follower: int = 1) -> Path:
    """Yaw of follower 1 vs time, degrees (Figs. 13, 19, 25)."""
    what = f"yaw of follower {follower}"
    ts = _rows(run)
    if ts is None or f"uav{follower}_yaw" not in ts:
        return _no_data(run, out_path, what, 3, run.ts_error or f"no follower {follower}")
    t = ts["t"]
    with plt.rc_context(STYLE):
        fig, ax = _new()
        ax.plot(t, _angles_deg(ts, follower, "yaw"), lw=1.0, color="C2", label="yaw ψ")
        _mark_events_in_time(ax, run)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("angle (deg)")
        ax.set_title(_title(run, what, 3), fontsize=9)
        ax.legend(loc="best")
        return save_figure(fig, out_path)


def _is_discrete(run: Run) -> bool:
    f = ((run.summary or {}).get("plugins") or {}).get("formation") or {}
    return "discrete" in str(f.get("name", ""))


def fig_sliding(run: Run, out_path, follower: int = 1) -> Path:
    """Sliding variable s_1 (x and y axes) vs time (Figs. 14, 20, 26)."""
    discrete = _is_discrete(run)
    what = f"sliding variable s_{follower}" + ("(k)" if discrete else "(t)")
    ts = _rows(run)
    if ts is None:
        return _no_data(run, out_path, what, 4, run.ts_error or "no data")
    sx, sy = ts.get(f"uav{follower}_sx"), ts.get(f"uav{follower}_sy")
    if sx is None or sy is None or not (np.isfinite(sx).any() or np.isfinite(sy).any()):
        return _no_data(run, out_path, what, 4,
                        "no sliding variable recorded\n(the protocol has none: empty CSV cells)")
    t = ts["t"]
    kw = {"drawstyle": "steps-post"} if discrete else {}
    with plt.rc_context(STYLE):
        fig, ax = _new()
        ax.plot(t, sx, lw=1.0, label=f"s_{follower},x", **kw)
        ax.plot(t, sy, lw=1.0, label=f"s_{follower},y", **kw)
        delta = run.plugin_report("delta")
        if math.isfinite(delta):
            ax.axhspan(-delta, delta, color="gray", alpha=0.2,
                       label=f"quasi-sliding band ±Δ, Δ = {delta:.3g}")
        ax.axhline(0.0, color="black", lw=0.6)
        _mark_events_in_time(ax, run)
        ax.set_xlabel("t (s)")
        # s = K e = k1 e_p + k2 e_v: with k1 in 1/s it has the units of a velocity.
        ax.set_ylabel("s (m/s)")
        ax.set_title(_title(run, what, 4), fontsize=9)
        ax.legend(loc="best")
        return save_figure(fig, out_path)


def sigma_f_series(run: Run):
    """(t, sigma_f) from the CSV column; the recomputation where the column is empty."""
    ts = run.timeseries
    if ts is None:
        return None, None
    t, s = ts["t"], ts.get("sigma_f")
    if s is None or not np.isfinite(s).any():
        s = M.sigma_f_recomputed(ts, M.circle_omega(run.summary, run.config))
    return t, s


def fig_sigma_f(run: Run, out_path) -> Path:
    """sigma_f(t), eq. (68), with the metric window shaded and its mean annotated (Figs. 15,
    21, 27)."""
    what = "formation tracking error σ_f(t)"
    t, s = sigma_f_series(run)
    if t is None:
        return _no_data(run, out_path, what, 5, run.ts_error or "no data")
    w = M.metric_window(run.summary, run.config)
    mean = M.window_mean(t, s, w)
    exp = M.paper_experiment(run.summary, run.name)
    paper = M.PAPER_SIGMA_F.get(exp, float("nan"))
    with plt.rc_context(STYLE):
        in_win = M.window_mask(t, w) & np.isfinite(s)
        zoom = bool(in_win.any()) and np.nanmax(s[in_win]) < 0.3 * np.nanmax(s)
        if zoom:
            # The window detail is invisible at the scale of sigma_f(0): a panel below zooms on
            # it (an inset would cover part of the transient).
            fig, axes = plt.subplots(2, 1, figsize=(8.0, 6.4), layout="constrained",
                                     height_ratios=[3, 2])
            ax, axes = axes[0], list(axes)
        else:
            fig, ax = _new((8.0, 4.6))
            axes = [ax]
        for k, a in enumerate(axes):
            a.plot(t, s, lw=1.1, color="C0", label="σ_f(t)" if k == 0 else None)
            a.axvspan(w[0], w[1], color="gold", alpha=0.25,
                      label=f"window [{w[0]:g}, {w[1]:g}] s" if k == 0 else None)
            if math.isfinite(mean):
                a.hlines(mean, w[0], w[1], colors="C3", lw=1.6,
                         label=f"our mean on window = {mean:.4f}" if k == 0 else None)
            if math.isfinite(paper):
                a.hlines(paper, w[0], w[1], colors="gray", lw=1.2, ls="--",
                         label=f"paper, Table 1: {paper:.4f}" if k == 0 else None)
        _mark_events_in_time(ax, run)
        top = np.nanmax(np.append(s[np.isfinite(s)], paper if math.isfinite(paper) else 0.0))
        ax.set_ylim(0, 1.12 * top if top > 0 else 1.0)
        if zoom:
            z = axes[1]
            lo, hi = w[0] - 0.1 * (w[1] - w[0]), w[1] + 0.02 * (w[1] - w[0])
            sel = (t >= lo) & (t <= hi) & np.isfinite(s)
            ztop = np.nanmax(np.append(s[sel], [mean, paper if math.isfinite(paper) else 0.0]))
            z.set_xlim(lo, hi)
            z.set_ylim(0, 1.15 * ztop if ztop > 0 else 1.0)
            z.set_title(f"zoom on the window [{w[0]:g}, {w[1]:g}] s", fontsize=9)
            z.set_xlabel("t (s)")
            z.set_ylabel("σ_f")
        if math.isfinite(mean):
            target = axes[-1]
            target.annotate(f"mean = {mean:.4f}", (0.5 * (w[0] + w[1]), mean),
                            textcoords="offset points", xytext=(0, 4), ha="center",
                            color="C3", fontsize=8, zorder=6,
                            bbox={"facecolor": "white", "alpha": 0.85, "lw": 0, "pad": 1})
        ax.set_xlabel("t (s)")
        ax.set_ylabel("σ_f (m, m/s: eq. (68))")
        ax.set_title(_title(run, what, 5), fontsize=9)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
        return save_figure(fig, out_path)


FIGURES = (
    ("trajectories", fig_trajectories),
    ("final_positions", fig_final_positions),
    ("pitch_roll", fig_pitch_roll),
    ("yaw", fig_yaw),
    ("sliding", fig_sliding),
    ("sigma_f", fig_sigma_f),
)


def run_figures(run: Run, out_dir) -> dict[str, Path]:
    """Every per-run figure into out_dir; {key: path}."""
    out_dir = Path(out_dir)
    return {key: fn(run, out_dir / FIGURE_NAMES[key]) for key, fn in FIGURES}


def fig_sigma_comparison(runs: list[Run], out_path, window=M.DEFAULT_WINDOW) -> Path:
    """sigma_f(t) of all runs on one log-scale axis."""
    with plt.rc_context(STYLE):
        fig, ax = _new((8.0, 5.0))
        styles = ["-", "--", "-.", ":"]
        n = 0
        for k, run in enumerate(runs):
            t, s = sigma_f_series(run)
            if t is None:
                continue
            s = np.where(s > 0, s, np.nan)
            label = run.name + ("" if run.complete else f" ({run.status})")
            ax.plot(t, s, lw=1.0, ls=styles[(k // 10) % 4], color=plt.get_cmap("tab10")(k % 10),
                    label=label)
            n += 1
        ax.axvspan(window[0], window[1], color="gold", alpha=0.2,
                   label=f"window [{window[0]:g}, {window[1]:g}] s")
        for exp, v in sorted(M.PAPER_SIGMA_F.items()):
            ax.axhline(v, color="gray", lw=0.7, ls="--")
            ax.annotate(f"paper Exp. {exp}: {v:g}", (0, v), xycoords=("axes fraction", "data"),
                        xytext=(3, 2), textcoords="offset points", fontsize=7, color="gray")
        ax.set_yscale("log")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("σ_f (eq. (68), log scale)")
        ax.set_title("Formation tracking error σ_f(t), all runs", fontsize=10)
        if n:
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
        return save_figure(fig, out_path)

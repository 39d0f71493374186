# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""report.md for a results folder: Table 1 beside the paper's, figures, topology, discussion."""

from __future__ import annotations

import math
import os
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import leaders
from . import metrics as M
from . import network
from . import plots
from .io import MARKED_EVENT_KINDS, Run, describe_event, find_runs

# The runs scripts/reproduce.sh writes for the paper's three experiments (quadrotor model).
EXPECTED_RUNS = ("exp1_printed", "exp1_switching", "exp1_exponential", "exp2", "exp3")
ORDER = EXPECTED_RUNS + ("consensus_baseline",)
POINTMASS_SUFFIX = "_pointmass"
FORMATION_TOLERANCE_M = 1.0  # "formation achieved": max final slot error below this
CROSSCHECK_RTOL = 1e-2


@dataclass
class Row:
    run: Run
    exp: int | None
    window: tuple
    t_end: float
    sigma_summary: float
    sigma_csv: float
    sigma_states: float
    max_slot_error: float

    @property
    def sigma(self) -> float:
        """Our mean sigma_f: the runner's summary, else the CSV column, else recomputed."""
        for v in (self.sigma_summary, self.sigma_csv, self.sigma_states):
            if math.isfinite(v):
                return v
        return float("nan")

    @property
    def paper(self) -> float:
        return M.PAPER_SIGMA_F.get(self.exp, float("nan"))

    @property
    def crashed(self) -> bool:
        """A vehicle flipped, hit the ground, collided or left the region (summary.json
        events): the run's σ_f is not the protocol's result."""
        return any(e.get("kind") in MARKED_EVENT_KINDS for e in self.run.events)

    @property
    def ratio(self) -> float:
        if (not self.run.complete or self.crashed or not math.isfinite(self.sigma)
                or not math.isfinite(self.paper)):
            return float("nan")
        return self.sigma / self.paper

    @property
    def window_covered(self) -> bool:
        return math.isfinite(self.t_end) and self.t_end >= self.window[1] - 1e-6

    @property
    def formation_achieved(self) -> bool:
        return self.run.complete and self.max_slot_error < FORMATION_TOLERANCE_M


def assumption1_line(summary: dict | None) -> str:
    """A report line when the leader's measured acceleration left Assumption 1's bounds
    (summary.json leader_acceleration.assumption1_holds false), else ""."""
    a = (summary or {}).get("leader_acceleration") or {}
    if a.get("assumption1_holds") is not False:
        return ""
    bounds = a.get("bounds") or [math.nan, math.nan]
    return (f"- **Assumption 1 does not hold**: the leader's measured acceleration left "
            f"[{bounds[0]:g}, {bounds[1]:g}] m/s² on {100 * (a.get('fraction_outside') or 0):.3g} % "
            f"of the steps, first at t = {fmt(a.get('first_violation_time_s'), 3)} s, by up to "
            f"{fmt(a.get('max_excess'), 3)} m/s²: Theorem 2's band is not guaranteed")


def _sort_key(run: Run):
    name = run.name
    pm = name.endswith(POINTMASS_SUFFIX)
    base = name[: -len(POINTMASS_SUFFIX)] if pm else name
    idx = ORDER.index(base) if base in ORDER else len(ORDER)
    return (idx, base, pm, name)


def analyse(run: Run) -> Row:
    exp = M.paper_experiment(run.summary, run.name)
    window = M.metric_window(run.summary, run.config)
    ts = run.timeseries
    nan = float("nan")
    sigma_csv = sigma_states = max_err = t_end = nan
    if ts is not None:
        t = ts["t"]
        t_end = float(t[-1])
        if "sigma_f" in ts:
            sigma_csv = M.window_mean(t, ts["sigma_f"], window)
        if M.followers(ts):
            s = M.sigma_f_recomputed(ts, M.circle_omega(run.summary, run.config))
            sigma_states = M.window_mean(t, s, window)
            errs = M.final_slot_errors(ts)
            if np.isfinite(errs).any():
                max_err = float(np.nanmax(errs))
    if math.isfinite(run.metric("max_final_slot_error_m")):
        max_err = run.metric("max_final_slot_error_m")
    if run.summary and isinstance(run.summary.get("sim_time_s"), (int, float)):
        t_end = float(run.summary["sim_time_s"])
    return Row(run, exp, window, t_end, run.metric("sigma_f_mean"), sigma_csv, sigma_states, max_err)


def fmt(x, digits=4, unit="") -> str:
    if x is None or not isinstance(x, (int, float)) or not math.isfinite(x):
        return "—"
    return f"{x:.{digits}f}{unit}"


def fmt_g(x, digits=4) -> str:
    if x is None or not isinstance(x, (int, float)) or not math.isfinite(x):
        return "—"
    return f"{x:.{digits}g}"


def _esc(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _rel(path: Path, start: Path) -> str:
    return Path(os.path.relpath(Path(path).resolve(), Path(start).resolve())).as_posix()


# ---------------------------------------------------------------------------------------------
# Topology


def _node_list(items) -> list:
    out = []
    for it in items or []:
        if isinstance(it, list) and it:
            out.append(it[0])
        else:
            out.append(it)
    return out


def topology_text(run: Run) -> str:
    """The graph of the run's config.toml [topology], with a spanning-tree check."""
    if run.config is None:
        why = f" ({run.config_error})" if run.config_error else ""
        return f"config.toml not found or unreadable{why}"
    topo = run.config.get("topology")
    if not isinstance(topo, dict):
        return "config.toml has no [topology] section"
    n = (run.config.get("vehicles") or {}).get("followers") or (run.summary or {}).get("n_followers")
    leader = [int(x) for x in _node_list(topo.get("leader_links")) if isinstance(x, int)]
    edges = []
    for e in topo.get("edges") or []:
        if isinstance(e, list) and len(e) >= 2:
            w = f" (w = {e[2]:g})" if len(e) == 3 and isinstance(e[2], (int, float)) else ""
            edges.append((int(e[0]), int(e[1]), w))
    gen = topo.get("generate")
    if gen and not edges and isinstance(n, int):
        edges = [(i, i + 1, "") for i in range(1, n)]
        if gen == "ring" and n > 2:
            edges.append((n, 1, ""))
    parts = [f"leader → follower(s) {', '.join(map(str, leader)) or 'none'}"
             f" (H = diag of a_i0: {sorted(leader)})"]
    if gen:
        parts.append(f"generated graph: `{gen}`")
    if edges:
        parts.append("follower edges `from → to` (`to` receives `from`'s state): "
                     + ", ".join(f"{a}→{b}{w}" for a, b, w in edges))
    else:
        parts.append("no follower-follower edges")
    # Assumption 2: a directed spanning tree rooted at the leader.
    if isinstance(n, int) and n > 0:
        reached = set(leader)
        frontier = list(leader)
        while frontier:
            a = frontier.pop()
            for x, y, _ in edges:
                if x == a and y not in reached:
                    reached.add(y)
                    frontier.append(y)
        missing = sorted(set(range(1, n + 1)) - reached)
        parts.append("directed spanning tree rooted at the leader: "
                     + ("yes (Assumption 2 holds)" if not missing
                        else f"NO, unreachable followers {missing}"))
    return "; ".join(parts)


# ---------------------------------------------------------------------------------------------
# Discussion generated from the data


def _by_model(rows):
    models = {}
    for r in rows:
        models.setdefault(r.run.vehicle_model, []).append(r)
    return models


def _orderings(model: str, rs: list[Row]) -> list[str]:
    """The paper's orderings of its experiments (Exp. 2 vs 3, Exp. 1 vs 2) on one vehicle model."""
    lines = []
    by_exp = {}
    for r in rs:
        # The paper's orderings are about its protocols as it ran them: a per-agent run over
        # a network (exp2_network) is a different question and stays out of them.
        if r.exp and math.isfinite(r.sigma) and not network.protocol_suffix(r.run.summary):
            by_exp.setdefault(r.exp, []).append(r)
    if 2 in by_exp and 3 in by_exp:
        for a in by_exp[2]:
            for b in by_exp[3]:
                agree = a.sigma < b.sigma
                lines.append(
                    f"- **Exp. 2 vs Exp. 3** ({model}): mean σ_f(`{a.run.name}`) = "
                    f"{fmt(a.sigma)} {'<' if agree else '≥'} mean σ_f(`{b.run.name}`) = "
                    f"{fmt(b.sigma)}: "
                    + ("agrees with the paper (a larger sampling period T widens the "
                       "quasi-sliding band and the error)." if agree else
                       "does NOT agree with the paper's claim that the error grows with T."))
    elif 2 in by_exp or 3 in by_exp:
        lines.append(f"- **Exp. 2 vs Exp. 3** ({model}): cannot compare, "
                     f"only Exp. {2 if 2 in by_exp else 3} has a complete run.")
    if 1 in by_exp and 2 in by_exp:
        for a in by_exp[1]:
            b = by_exp[2][0]
            agree = a.sigma < b.sigma
            lines.append(
                f"- **Exp. 1 vs Exp. 2** ({model}): mean σ_f(`{a.run.name}`) = {fmt(a.sigma)} "
                f"{'<' if agree else '≥'} {fmt(b.sigma)} (`{b.run.name}`): "
                + ("consistent with the paper's reading of Exp. 1 as the T → 0 limit."
                   if agree else "not the paper's ordering (continuous below discrete)."))
    return lines


def discussion(rows: list[Row]) -> list[str]:
    lines = []
    # A run in which a vehicle crashed is no evidence for or against the protocol.
    done = [r for r in rows if r.run.complete and not r.crashed]
    achieved = [r for r in done if r.formation_achieved]
    missed = [r for r in done if not r.formation_achieved]
    not_done = [r for r in rows if not r.run.complete]
    lines.append(f"- **Formation achieved** (complete run, max final slot error < "
                 f"{FORMATION_TOLERANCE_M:g} m): "
                 + (", ".join(f"`{r.run.name}` ({fmt(r.max_slot_error, 3)} m)" for r in achieved)
                    or "none") + ".")
    if missed:
        lines.append("- **Formation not achieved** at the final time: "
                     + ", ".join(f"`{r.run.name}` ({fmt(r.max_slot_error, 3)} m)" for r in missed)
                     + ".")
    if not_done:
        lines.append("- **Incomplete runs** (no result; shown for diagnosis only): "
                     + ", ".join(f"`{r.run.name}` ({r.run.status}, t = {fmt(r.t_end, 2)} s: "
                                 f"{_esc(r.run.error or '?')})" for r in not_done) + ".")
    for model, rs in sorted(_by_model(done).items()):
        lines.extend(_orderings(model, rs))
    bounded = [r for r in done if math.isfinite(r.run.plugin_report("error_bound"))
               and math.isfinite(r.sigma)]
    for r in bounded:
        b = r.run.plugin_report("error_bound")
        lines.append(f"- **Error bound (47)** `{r.run.name}`: measured mean σ_f = {fmt(r.sigma)} "
                     f"{'≤' if r.sigma <= b else '>'} bound {fmt_g(b)} "
                     f"(Δ = {fmt_g(r.run.plugin_report('delta'))}); the bound assumes equal "
                     "position and velocity error norms, so it is indicative.")
    ratios = [r for r in done if math.isfinite(r.ratio)]
    if ratios:
        lines.append("- **Ours / paper**: " + ", ".join(
            f"`{r.run.name}` {fmt(r.ratio, 3)}" for r in ratios)
            + ". The paper's numbers come from Gazebo with its own vehicle and controller "
              "tuning; ratios near 1 are not expected to be exact.")
    return lines


# ---------------------------------------------------------------------------------------------
# The report


def _spread(values) -> str:
    v = [x for x in (values or []) if isinstance(x, (int, float)) and math.isfinite(x)]
    if not v:
        return "—"
    return f"{np.mean(v):.1f} [{min(v):.1f}, {max(v):.1f}]"


def motion_lines(rows: list[Row]) -> list[str]:
    """How much the followers rock in the metric window (summary.json metrics *_in_window)."""
    have = [r for r in rows if ((r.run.summary or {}).get("metrics") or {}).get(
        "rms_tilt_deg_in_window") is not None]
    if not have:
        return []
    L = ["## Follower motion in the metric window", "",
         "Per follower, over the metric window: RMS tilt (angle of body z from vertical), the "
         "dominant frequency of the tilt oscillation (0.3-5 Hz) and the RMS variation of the "
         "collective thrust (control effort); mean [min, max] over the followers, frequency as "
         "the median. A point mass never tilts.", "",
         "| Run | Vehicle model | Attitude plugin | RMS tilt (deg) | Rocking (Hz) | "
         "RMS thrust variation (N) | Max tilt in window (deg) |", "|---|---|---|---|---|---|---|"]
    for r in have:
        m = r.run.summary["metrics"]
        hz = [x for x in m.get("tilt_oscillation_hz_in_window") or [] if isinstance(x, (int, float))]
        plugin = (((r.run.summary.get("plugins") or {}).get("attitude") or {}).get("name")) or "—"
        L.append(f"| `{r.run.name}` | {_esc(r.run.vehicle_model)} | {_esc(plugin)} | "
                 f"{_spread(m.get('rms_tilt_deg_in_window'))} | "
                 f"{f'{np.median(hz):.2f}' if hz else '—'} | "
                 f"{_spread(m.get('rms_thrust_variation_n_in_window'))} | "
                 f"{fmt(r.run.metric('max_follower_tilt_deg_in_window'), 1)} |")
    L.append("")
    return L


def _per_follower(values, digits=1) -> str:
    if not values:
        return "—"
    return ", ".join("—" if v is None else f"{v:.{digits}f}" for v in values)


def transient_lines(rows: list[Row]) -> list[str]:
    """The reaching transient per follower (summary.json: max_slot_distance_after_5s_m,
    time_within_1m_s, peak_demanded_accel, peak_delivered_accel)."""
    have = [r for r in rows if ((r.run.summary or {}).get("metrics") or {}).get(
        "max_slot_distance_after_5s_m") is not None]
    if not have:
        return []
    L = ["## Reaching transient", "",
         "Per follower (1, 2, ...): the largest distance from its slot after t = 5 s, the last "
         "time it was farther than 1 m from it (— if it still is at the end), and the peak "
         "demanded (the formation's command) and delivered (from the true velocity) horizontal "
         "acceleration.", "",
         "| Run | Largest slot distance after 5 s (m) | Within 1 m from (s) | "
         "Peak demanded accel (m/s²) | Peak delivered accel (m/s²) |", "|---|---|---|---|---|"]
    for r in have:
        m = r.run.summary["metrics"]
        L.append(f"| `{r.run.name}` | {_per_follower(m.get('max_slot_distance_after_5s_m'))} | "
                 f"{_per_follower(m.get('time_within_1m_s'))} | "
                 f"{_per_follower(m.get('peak_demanded_accel'))} | "
                 f"{_per_follower(m.get('peak_delivered_accel'))} |")
    L.append("")
    return L


EVENT_MARK = "†"


def event_notes(rows: list[Row]) -> list[str]:
    """Footnotes of Table 1: per run with safety events, how many, of which kinds, the first
    severe one in the runner's words, and whether its σ_f may be read as a result."""
    lines = []
    for k, r in enumerate(rows, 1):
        events = r.run.events
        severe = [e for e in events if e.get("kind") in MARKED_EVENT_KINDS]
        first = (severe or events or [None])[0]
        by_kind = ((r.run.summary or {}).get("events") or {}).get("by_kind") or {}
        kinds = ", ".join(f"{kind} {n}" for kind, n in by_kind.items()) or "?"
        n = r.run.event_count
        verdict = ("its σ_f is not a result (in parentheses, no ratio)" if r.crashed
                   else "near misses only: σ_f stands, read it with care")
        lines.append(f"{EVENT_MARK}{k} `{r.run.name}`: {n} safety event{'s' if n != 1 else ''} "
                     f"({kinds})" + (f"; {_esc(describe_event(first))}" if first else "")
                     + f"; {verdict}.")
        lines.append("")
    return lines


def _copy(src: Path, dst: Path) -> Path:
    dst.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(src, dst)
    return dst


def _status_cell(run: Run) -> str:
    if run.complete:
        return "yes"
    return f"**NO** ({run.status})"


def _header_lines(results_dir: Path, out_dir: Path, n_runs: int) -> list[str]:
    return [
        "# mjformation: distributed sliding-mode formation tracking, reproduction report",
        "",
        "Paper: J. Wang, L. Han, X. Dong et al., \"Distributed sliding mode control for "
        "time-varying formation tracking of multi-UAV system with a dynamic leader\", "
        "Aerospace Science and Technology 111 (2021) 106549, section 6 (Experiments 1-3, "
        "Figs. 9-27, Table 1).",
        "",
        f"Results folder: `{_rel(results_dir, out_dir)}` (relative to this report); "
        f"{n_runs} run director{'y' if n_runs == 1 else 'ies'}.",
        "",
    ]


def _runs_lines(rows: list[Row]) -> list[str]:
    """The runs present, and the expected ones missing."""
    L = ["## Runs", ""]
    names = {r.run.name for r in rows}
    for r in rows:
        extra = "" if r.run.complete else f" — {_esc(r.run.error or '')}"
        L.append(f"- `{r.run.name}`: {r.run.status}{extra}")
    missing = [n for n in EXPECTED_RUNS if n not in names]
    if any(n.endswith(POINTMASS_SUFFIX) for n in names):
        missing += [n + POINTMASS_SUFFIX for n in EXPECTED_RUNS
                    if n + POINTMASS_SUFFIX not in names]
    L.append("")
    if missing:
        L.append("**Missing runs** (expected, not found in the results folder): "
                 + ", ".join(f"`{n}`" for n in missing) + ".")
    else:
        L.append("No expected run is missing.")
    L.append("")
    return L


def _table1_cell(r: Row, notes: list[Row]) -> str:
    """Our mean σ_f as Table 1 shows it: in parentheses when it is no result, marked when the
    run had a safety event (its footnote appended to `notes`)."""
    ours = fmt(r.sigma)
    if not r.run.complete:
        ours = f"({ours}) {r.run.status}" if ours != "—" else f"— ({r.run.status})"
    elif r.crashed:
        ours = f"({ours})"
    elif not r.window_covered:
        ours += " (window not covered)"
    if r.run.event_count:
        notes.append(r)
        ours += f" {EVENT_MARK}{len(notes)}"
    return ours


def _table1_lines(rows: list[Row]) -> list[str]:
    L = ["## Table 1, side by side with the paper", ""]
    L.append("Mean of σ_f(t), eq. (68), over the metric window (the paper's t ∈ [25, 40] s). "
             "Paper values: Gazebo, Table 1. Δ and the error bound are what the formation "
             "plugin reports (discrete protocol: quasi-sliding band, eq. (49), and bound (47)). "
             "An incomplete run is never a result: its partial number is in parentheses and it "
             "has no ratio.")
    L.append("")
    L.append("| Run | Paper exp. | Vehicle model | Protocol | Ours: mean σ_f | Paper | "
             "Ours / paper | Δ | Error bound | Max final slot error (m) | Complete |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|")
    notes = []  # footnotes of the runs with safety events
    for r in rows:
        ours = _table1_cell(r, notes)
        L.append("| " + " | ".join([
            f"`{r.run.name}`",
            str(r.exp) if r.exp else "—",
            _esc(r.run.vehicle_model),
            _esc(M.protocol_description(r.run.summary, r.run.config)
                 + network.protocol_suffix(r.run.summary)),
            ours,
            fmt(r.paper),
            fmt(r.ratio, 3),
            fmt_g(r.run.plugin_report("delta")),
            fmt_g(r.run.plugin_report("error_bound")),
            fmt(r.max_slot_error, 3),
            _status_cell(r.run),
        ]) + " |")
    L.append("")
    L.extend(event_notes(notes))
    L.append("Paper protocols: " + "; ".join(f"Exp. {k}: {v}" for k, v in
                                              sorted(M.PAPER_PROTOCOL.items())) + ".")
    L.append("")
    return L


def _crosscheck_lines(rows: list[Row]) -> list[str]:
    L = ["### Cross-check of the runner's σ_f", ""]
    L.append("The runner's online mean (summary.json), the mean of the CSV's `sigma_f` column and "
             "σ_f recomputed here from the recorded states and slots (f_iv = ω J f_ip for the "
             "circle shape, else the numerical derivative of f_ip), each over the window.")
    L.append("")
    L.append("| Run | Window (s) | summary.json | CSV column | Recomputed from states | Agree |")
    L.append("|---|---|---|---|---|---|")
    for r in rows:
        vals = [v for v in (r.sigma_summary, r.sigma_csv, r.sigma_states) if math.isfinite(v)]
        if len(vals) >= 2:
            ok = max(vals) - min(vals) <= CROSSCHECK_RTOL * max(abs(max(vals)), 1e-12)
            agree = "yes" if ok else f"**no** (spread > {CROSSCHECK_RTOL:.0%})"
        else:
            agree = "—"
        L.append(f"| `{r.run.name}` | [{r.window[0]:g}, {r.window[1]:g}] | {fmt(r.sigma_summary)} "
                 f"| {fmt(r.sigma_csv)} | {fmt(r.sigma_states)} | {agree} |")
    L.append("")
    return L


def _robustness_lines(results_dir: Path) -> list[str]:
    """The robustness map of scripts/robustness_map.sh, when it was run."""
    robustness_md = results_dir / "robustness" / "map.md"
    if not robustness_md.is_file():
        return []
    return [
        "## Robustness map (experiment × tilt_max × vehicle × formation law)",
        "",
        "From `scripts/robustness_map.sh` (each attitude plugin at its default gains; "
        "\"reached\": every follower within 1 m of its slot at the end; mean ± 95 % "
        "CI half-width over the seeds):",
        "",
        robustness_md.read_text().rstrip("\n"),
        "",
    ]


def _topology_lines(runs: list[Run]) -> list[str]:
    L = ["## Interaction topology", ""]
    L.append("The paper's Fig. 8 gives the follower-follower edges only in the figure, not in the "
             "text (the text says only that follower 1 alone receives the leader). The graph "
             "actually used, read from each run's `config.toml` `[topology]` section:")
    L.append("")
    groups = {}
    for r in runs:
        groups.setdefault(topology_text(r), []).append(r.name)
    for text, members in groups.items():
        L.append(f"- {', '.join(f'`{m}`' for m in members)}: {text}")
    L.append("")
    return L


def _findings_lines(rows: list[Row]) -> list[str]:
    """What these runs show, generated from their data: the report's opening section."""
    return ["## Findings", "", "Generated from the runs below (the tables and figures follow):", ""] \
        + discussion(rows) + [""]


def _commentary_lines(results_dir: Path) -> list[str]:
    """The experiment authors' commentary (`discussion.md` beside the runs), after the figures."""
    disc = results_dir / "discussion.md"
    if not disc.is_file():
        return []
    return ["## Commentary from the experiment authors (`discussion.md`)", "",
            disc.read_text().rstrip("\n"), ""]


def _run_summary_lines(r: Row) -> list[str]:
    """A run's status, safety events and numbers, at the top of its section."""
    run = r.run
    L = [f"### `{run.name}`", ""]
    if not run.complete:
        L.append(f"> **{run.status.upper()}** — not a result. {_esc(run.error or '')} "
                 f"(recorded up to t = {fmt(r.t_end, 2)} s)")
        L.append("")
    if run.event_count:
        shown = run.events[:5]
        more = run.event_count - len(shown)
        L.append(f"> **{run.event_count} SAFETY EVENT{'S' if run.event_count > 1 else ''}**"
                 + (" — σ_f is not a result" if r.crashed else "") + ": "
                 + "; ".join(_esc(describe_event(e)) for e in shown)
                 + (f"; {more} more in summary.json" if more > 0 else "") + ".")
        L.append("")
    L.append(f"- experiment: {_esc(run.label)}; paper experiment: {r.exp or '—'}; "
             f"vehicle model: {_esc(run.vehicle_model)}")
    L.append(f"- protocol: {_esc(M.protocol_description(run.summary, run.config))}"
             f"{_esc(network.protocol_suffix(run.summary))}")
    L.append(f"- mean σ_f on [{r.window[0]:g}, {r.window[1]:g}] s: {fmt(r.sigma)}; "
             f"σ_f(0) = {fmt(run.metric('sigma_f_initial'))}; "
             f"σ_f(end) = {fmt(run.metric('sigma_f_final'))}")
    L.append(f"- max final slot error: {fmt(r.max_slot_error, 3)} m; min separation: "
             f"{fmt(run.metric('min_separation_m'), 3)} m; reaching time: "
             f"{fmt(run.metric('reaching_time_s'), 2)} s; actuator saturation time: "
             f"{fmt(run.metric('saturation_time_s'), 3)} s")
    assumption = assumption1_line(run.summary)
    if assumption:
        L.append(assumption)
    L.extend(network.lines(run.summary))
    L.append("")
    return L


def _run_figure_lines(run: Run, fig_dir: Path, out_dir: Path) -> list[str]:
    """A run's figures (network, estimate, time series), snapshots and video, written or copied
    under out_dir."""
    # Imported here only: a report whose runs have no estimator never needs it.
    from . import estimation_figure as EF

    L = []
    net_fig = network.figure(run, fig_dir / run.name / network.FIGURE_NAME)
    if net_fig is not None:
        L.append(f"![{run.name} network]({_rel(net_fig, out_dir)})")
        L.append("")
    est_fig = EF.figure(run, fig_dir / run.name / EF.FIGURE_NAME)
    if est_fig is not None:  # an [estimator] other than passthrough
        L.append(f"![{run.name} estimate against truth]({_rel(est_fig, out_dir)})")
        L.append("")
    if run.timeseries is not None:
        figs = plots.run_figures(run, fig_dir / run.name)
        for key, path in figs.items():
            L.append(f"![{run.name} {key}]({_rel(path, out_dir)})")
            L.append("")
    else:
        L.append(f"No figures: {_esc(run.ts_error or 'no timeseries.csv')}.")
        L.append("")
    snaps = run.snapshots()
    if snaps:
        L.append("Snapshots (offscreen renders):")
        L.append("")
        for s in snaps:
            dst = _copy(s, out_dir / "snapshots" / run.name / s.name)
            m = re.match(r"t(\d+(?:\.\d+)?)\.png$", s.name)
            cap = f"t = {float(m.group(1)):g} s" if m else s.name
            L.append(f"![{run.name} snapshot {cap}]({_rel(dst, out_dir)})")
            L.append("")
    if run.video is not None:
        L.append(f"Video: [{run.name}/video.mp4]({_rel(run.video, out_dir)})")
        L.append("")
    return L


def write_report(results_dir, out_dir) -> Path:
    """Writes out_dir/report.md (+ figures, snapshots). Raises FileNotFoundError when
    results_dir holds no run directory."""
    results_dir, out_dir = Path(results_dir), Path(out_dir)
    runs = sorted((r for r in find_runs(results_dir)
                   if r.path.resolve() != out_dir.resolve()), key=_sort_key)
    if not runs:
        raise FileNotFoundError(f"{results_dir}: no run directories (sub-folders with "
                                "summary.json or timeseries.csv)")
    out_dir.mkdir(parents=True, exist_ok=True)
    fig_dir = out_dir / "figures"
    rows = [analyse(r) for r in runs]
    # Findings and Table 1 first; the evidence, the commentary and each run's detail after.
    L = _header_lines(results_dir, out_dir, len(runs))
    L += _findings_lines(rows)
    L += _table1_lines(rows)
    L += _runs_lines(rows)
    L += _crosscheck_lines(rows)
    L += motion_lines(rows)  # inner-loop motion: tilt, oscillation, thrust variation
    L += transient_lines(rows)
    L += _robustness_lines(results_dir)
    comp = plots.fig_sigma_comparison(runs, fig_dir / "sigma_f_all_runs.png",
                                      rows[0].window if rows else M.DEFAULT_WINDOW)
    L += ["## σ_f(t) of all runs", "", f"![sigma_f of all runs, log scale]({_rel(comp, out_dir)})",
          ""]
    L += _topology_lines(runs)
    L += leaders.section(results_dir, out_dir)  # non-cooperative leaders, when they were run
    L += _commentary_lines(results_dir)
    L += ["## Runs in detail", ""]
    for r in rows:
        L += _run_summary_lines(r)
        L += _run_figure_lines(r.run, fig_dir, out_dir)
    path = out_dir / "report.md"
    path.write_text("\n".join(L).rstrip("\n") + "\n")
    return path

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The benchmark's metrics of one run directory (docs/BENCHMARK.md, "Metrics", items 1-7).

Computed here from timeseries.csv and summary.json rather than by the runner: summary.json's
bytes are compared by dev/bytecheck.sh, and these metrics are the benchmark's, not every run's.
Notation as in docs/BENCHMARK.md: followers i = 1..N, samples k with times t_k, the window
W = [t_a, t_b] (summary.json metrics.sigma_f_window), p_i the horizontal position, p_i^* the slot
(columns slot_x, slot_y), u_i the commanded horizontal acceleration (ax_cmd, ay_cmd).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .io import read_summary, read_timeseries
from .metrics import followers, window_mask

# Reaching band b of metric 3, m (docs/BENCHMARK.md states it for the board).
DEFAULT_BAND_M = 1.0
# The safety events that make a run fail (a near miss or leaving the region does not).
FAILING_EVENTS = ("flip", "ground_impact", "collision")
METRICS_FILE = "benchmark_metrics.json"


def _pairs(ts: dict, fs: list[int], suffix: tuple[str, str]) -> np.ndarray:
    """Array (rows, N, 2) of the followers' columns uav<i>_<suffix[0]>, uav<i>_<suffix[1]>."""
    return np.stack([np.stack([ts[f"uav{i}_{suffix[0]}"], ts[f"uav{i}_{suffix[1]}"]], axis=1)
                     for i in fs], axis=1)


def slot_errors(ts: dict) -> np.ndarray:
    """||p_i(t_k) - p_i^*(t_k)||, array (rows, N)."""
    fs = followers(ts)
    d = _pairs(ts, fs, ("px", "py")) - _pairs(ts, fs, ("slot_x", "slot_y"))
    return np.hypot(d[:, :, 0], d[:, :, 1])


def rms_slot_error(ts: dict, window) -> float:
    """Metric 2: sqrt( (1/(K N)) sum_{k in W} sum_i ||p_i - p_i^*||^2 ), m."""
    e = slot_errors(ts)[window_mask(ts["t"], window)]
    return float(np.sqrt(np.mean(e**2))) if e.size else math.nan


def reaching_time(ts: dict, band: float) -> float:
    """Metric 3: the first t_k from which max_i ||p_i - p_i^*|| <= band at every later sample;
    inf when the last sample is outside the band (never reached to stay)."""
    worst = np.max(slot_errors(ts), axis=1)
    outside = np.flatnonzero(~(worst <= band))  # a NaN error counts as outside
    if outside.size == 0:
        return float(ts["t"][0])
    last = outside[-1]
    return math.inf if last == len(worst) - 1 else float(ts["t"][last + 1])


def _commands(ts: dict, window) -> tuple[np.ndarray, np.ndarray]:
    """(t, u) inside the window: u is array (K, N, 2)."""
    mask = window_mask(ts["t"], window)
    return ts["t"][mask], _pairs(ts, followers(ts), ("ax_cmd", "ay_cmd"))[mask]


def chattering_index(ts: dict, window) -> float:
    """Metric 4: (1/(N (t_b - t_a))) sum_i sum_k ||u_i(t_k) - u_i(t_{k-1})|| over consecutive
    samples both in W, m/s^3. At the record rate: variation faster than it is not seen."""
    t, u = _commands(ts, window)
    if len(t) < 2:
        return math.nan
    steps = np.linalg.norm(np.diff(u, axis=0), axis=2)  # (K-1, N)
    return float(np.sum(steps) / (u.shape[1] * (t[-1] - t[0])))


def control_effort(ts: dict, window) -> float:
    """Metric 5: (1/N) sum_i sum_{k in W} ||u_i(t_k)||^2 h, h the record step, m^2/s^3."""
    t, u = _commands(ts, window)
    if len(t) < 2:
        return math.nan
    h = float(np.median(np.diff(t)))
    return float(np.sum(u**2) * h / u.shape[1])


def messages_per_second(summary: dict, n_followers: int) -> float | None:
    """Metric 7 (per-agent runs; None in central mode, which sends nothing): the messages the
    followers sent, per follower and second of flight, (1/(N t_end)) sum over links from a
    follower of (state messages + exchange-round messages) + the R_i each sent up to the
    central solve over links; a message to k out-neighbours is k messages (one per link)."""
    net = summary.get("network")
    sim_time = summary.get("sim_time_s")
    if not net or not sim_time or n_followers < 1:
        return None
    sent = sum(link["sent"] + link.get("round_messages_sent", 0)
               for link in net.get("links", []) if link["from"] != 0)
    solver = (net.get("rounds_over_links") or {}).get("solver") or {}
    sent += sum(link["up_r"]["sent"] for link in solver.get("links", []))
    return sent / (n_followers * sim_time)


def failing_events(summary: dict) -> dict[str, int]:
    """Count of each failing safety event kind in summary.json "events" (absent: none)."""
    by_kind = summary.get("events", {}).get("by_kind", {})
    return {k: int(by_kind[k]) for k in FAILING_EVENTS if by_kind.get(k)}


def failure_reason(summary: dict, values: dict) -> str | None:
    """Why the run scores as failed, or None: a failing safety event, a run that did not
    complete, or a non-finite score."""
    events = failing_events(summary)
    if events:
        return "safety: " + ", ".join(f"{n} {k}" for k, n in events.items())
    if not summary.get("complete", False):
        return "incomplete: " + str(summary.get("error") or "stopped early")
    for key in ("sigma_f_mean", "rms_slot_error_m", "chattering_index", "control_effort"):
        v = values.get(key)
        if v is None or not math.isfinite(v):
            return f"non-finite {key}"
    return None


def run_metrics(run_dir, band: float = DEFAULT_BAND_M) -> dict:
    """Metrics 1-7 of docs/BENCHMARK.md for one run directory, with "failed" (reason or None).
    Infinite reaching time is written as None (JSON has no infinity)."""
    d = Path(run_dir)
    summary = read_summary(d / "summary.json")
    ts = read_timeseries(d / "timeseries.csv")
    m = summary.get("metrics", {})
    window = tuple(m.get("sigma_f_window") or (0.0, float(ts["t"][-1])))
    reach = reaching_time(ts, band)
    values = {
        "window_s": list(window),
        "sigma_f_mean": m.get("sigma_f_mean"),
        "rms_slot_error_m": rms_slot_error(ts, window),
        "reaching_band_m": band,
        "reaching_time_s": reach if math.isfinite(reach) else None,
        "chattering_index": chattering_index(ts, window),
        "control_effort": control_effort(ts, window),
        "min_separation_m": m.get("min_separation_m"),
        "safety_events": failing_events(summary),
        "messages_per_s": messages_per_second(summary, len(followers(ts))),
    }
    values["failed"] = failure_reason(summary, values)
    return values


def not_applicable(reason: str) -> dict:
    """The metrics of a cell the law cannot fly (a per-agent scenario and a law without a
    per-agent version): no number, and not a failure."""
    return {"not_applicable": reason, "failed": None}


def write_metrics(run_dir, values: dict) -> dict:
    """values written to <run_dir>/benchmark_metrics.json (the cell's 'done' mark), non-finite
    floats as null."""
    finite = {k: None if isinstance(v, float) and not math.isfinite(v) else v
              for k, v in values.items()}
    Path(run_dir).mkdir(parents=True, exist_ok=True)
    (Path(run_dir) / METRICS_FILE).write_text(json.dumps(finite, indent=2) + "\n")
    return values


def write_run_metrics(run_dir, band: float = DEFAULT_BAND_M) -> dict:
    """run_metrics, also written to <run_dir>/benchmark_metrics.json (the cell's 'done' mark)."""
    return write_metrics(run_dir, run_metrics(run_dir, band))

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Statistics of repeated runs and the Markdown tables of docs/PEERS.md."""

import math
import statistics


def fmt(x, digits=3):
    """A number with `digits` significant digits; '-' for None or NaN; thousands separated."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if isinstance(x, int):
        return f"{x:,}"
    if x == 0:
        return "0"
    mag = int(math.floor(math.log10(abs(x))))
    if mag >= digits - 1:
        return f"{round(x):,}"
    return f"{x:.{max(0, digits - 1 - mag)}f}"


def spread(values, digits=3):
    """'median [min - max] (k)' of a list of numbers; the median alone for one value."""
    vals = [v for v in values if v is not None and not (isinstance(v, float) and math.isnan(v))]
    if not vals:
        return "-"
    if len(vals) == 1:
        return f"{fmt(vals[0], digits)} (1)"
    return f"{fmt(statistics.median(vals), digits)} [{fmt(min(vals), digits)}-{fmt(max(vals), digits)}] ({len(vals)})"


def speed_row(runs, n_vehicles):
    """Per run: real-time factor sim_s / wall_s and vehicle-steps per second; their medians."""
    rtf = [r["sim_s"] / r["wall_s"] for r in runs if r.get("wall_s")]
    vsteps = [n_vehicles * r["physics_steps"] / r["wall_s"] for r in runs if r.get("wall_s")]
    return {
        "rtf": rtf, "vsteps": vsteps,
        "rtf_median": statistics.median(rtf) if rtf else float("nan"),
        "vsteps_median": statistics.median(vsteps) if vsteps else float("nan"),
        "vehicle_seconds_per_s": n_vehicles * statistics.median(rtf) if rtf else float("nan"),
    }


def ratio(ours, theirs):
    """How many times faster mjformation flies the same vehicle-seconds: ours / theirs."""
    if not ours or not theirs or math.isnan(ours) or math.isnan(theirs):
        return float("nan")
    return ours / theirs


def markdown(headers, rows, align=None):
    """A GitHub Markdown table; align: one of 'l', 'r' per column (default: first l, rest r)."""
    align = align or ["l"] + ["r"] * (len(headers) - 1)
    sep = ["---" if a == "l" else "---:" for a in align]
    out = ["| " + " | ".join(headers) + " |", "| " + " | ".join(sep) + " |"]
    for row in rows:
        if len(row) != len(headers):
            raise ValueError(f"row has {len(row)} cells, the table {len(headers)}: {row}")
        out.append("| " + " | ".join(str(c).replace("|", "/") for c in row) + " |")
    return "\n".join(out)

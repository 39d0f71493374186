# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The robustness map under the acceleration limit (scripts/robustness_map.sh): experiment x
vehicle/attitude plugin x tilt_max x formation law (the paper's (48) or the input-constrained
reaching law), seeds of start jitter, each cell with its 95 % Student-t confidence interval.

Layout read: MAP_DIR/<experiment>__<vehicle>__<law>/sweep.json and, per run,
MAP_DIR/<experiment>__<vehicle>__<law>/<run>/summary.json, through the loader (mjfanalysis.io).
"""

import csv
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from .io import load_sweep
from .leaders import mean_ci

REACHED_TOLERANCE_M = 1.0   # "reached": every follower within 1 m of its slot at the end
GOAL_DISTANCE_M = 15.0      # the study's goal: no follower farther than this after t = 5 s
NAN = float("nan")
FOLDER_RE = re.compile(r"^(?P<exp>[a-z0-9_]+?)__(?P<vehicle>[a-z_]+)__(?P<law>paper|constrained)$")
LIMIT_RE = re.compile(r"pointmass_lim([0-9.]+)\.xml")


@dataclass
class Cell:
    experiment: str
    vehicle: str
    law: str
    tilt_max: float
    runs: list = field(default_factory=list)  # summary.json dicts (complete or not)
    refused: int = 0

    def complete(self):
        return [r for r in self.runs if r.get("complete")]

    def values(self, fn):
        out = []
        for r in self.complete():
            try:
                out.append(float(fn(r["metrics"])))
            except (TypeError, ValueError, KeyError):
                out.append(NAN)
        return out

    def reached_fraction(self) -> float:
        done = self.complete()
        if not done:
            return NAN
        ok = [r for r in done if r["metrics"].get("max_final_slot_error_m", math.inf) < REACHED_TOLERANCE_M]
        return len(ok) / len(done)

    def stats(self) -> dict:
        def worst(key):
            return lambda m: max(x if x is not None else math.inf for x in m[key])
        return {
            "sigma_f": mean_ci(self.values(lambda m: m["sigma_f_mean"])),
            "after5": mean_ci(self.values(worst("max_slot_distance_after_5s_m"))),
            "settle": mean_ci(self.values(worst("time_within_1m_s"))),
            "demand": mean_ci(self.values(worst("peak_demanded_accel"))),
            "delivered": mean_ci(self.values(worst("peak_delivered_accel"))),
        }


def _tilt_of(row: dict) -> float:
    if "attitude.tilt_max" in row:
        return float(row["attitude.tilt_max"])
    m = LIMIT_RE.search(row.get("vehicles.model", ""))
    return math.atan(float(m.group(1)) / 9.81) if m else NAN


def read_map(map_dir: Path) -> list:
    cells = {}
    for folder in sorted(p for p in Path(map_dir).iterdir() if p.is_dir()):
        m = FOLDER_RE.match(folder.name)
        if not m or not (folder / "sweep.json").is_file():
            continue
        sweep = load_sweep(folder)
        for entry in sweep.runs:
            tilt = round(_tilt_of(entry), 2)
            key = (m["exp"], m["vehicle"], m["law"], tilt)
            cell = cells.setdefault(key, Cell(m["exp"], m["vehicle"], m["law"], tilt))
            summary = sweep.run(entry).summary
            if summary is not None:
                cell.runs.append(summary)
            if "refused" in (entry.get("error") or ""):
                cell.refused += 1
    return sorted(cells.values(), key=lambda c: (c.experiment, c.vehicle, c.tilt_max, c.law))


def _ci(mean_half, digits=2) -> str:
    mean, half = mean_half
    if not math.isfinite(mean):
        return "-"
    if not math.isfinite(half):
        return f"{mean:.{digits}f}"
    return f"{mean:.{digits}f} ± {half:.{digits}f}"


def markdown(cells: list) -> list:
    lines = [
        "| experiment | vehicle | tilt_max (rad) | law | runs | reached | mean sigma_f [25, 40] s "
        "| worst slot distance after 5 s (m) | worst time to stay within 1 m (s) "
        "| peak demanded / delivered accel (m/s^2) |",
        "|---|---|---:|---|---:|---:|---:|---:|---:|---:|",
    ]
    for c in cells:
        done = c.complete()
        if not done:
            why = "refused" if c.refused else "no complete run"
            lines.append(f"| `{c.experiment}` | {c.vehicle} | {c.tilt_max:.2f} | {c.law} | 0 | {why} "
                         "| - | - | - | - |")
            continue
        s = c.stats()
        reached = c.reached_fraction()
        lines.append(
            f"| `{c.experiment}` | {c.vehicle} | {c.tilt_max:.2f} | {c.law} | {len(done)} "
            f"| {'**' if reached == 1 else ''}{reached * 100:.0f} %{'**' if reached == 1 else ''} "
            f"| {_ci(s['sigma_f'], 3)} | {_ci(s['after5'], 1)} | {_ci(s['settle'], 1)} "
            f"| {_ci(s['demand'], 1)} / {_ci(s['delivered'], 1)} |")
    return lines


def write_csv(cells: list, path: Path) -> None:
    with Path(path).open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["experiment", "vehicle", "tilt_max", "law", "runs", "reached_fraction",
                    "sigma_f_mean", "sigma_f_ci95", "after5_worst_m", "after5_ci95",
                    "settle_worst_s", "settle_ci95", "peak_demand", "peak_delivered"])
        for c in cells:
            s = c.stats()
            w.writerow([c.experiment, c.vehicle, c.tilt_max, c.law, len(c.complete()),
                        c.reached_fraction(), *s["sigma_f"], *s["after5"], *s["settle"],
                        s["demand"][0], s["delivered"][0]])


VEHICLES = ("geometric", "pd_cascade_fixed", "pointmass")
LAWS = ("paper", "constrained")


def _cell_text(c) -> str:
    if c is None:
        return "not run"
    if not c.complete():
        return "refused" if c.refused else "no complete run"
    s = c.stats()
    reached = c.reached_fraction()
    head = f"**{reached * 100:.0f} %**" if reached == 1 else f"{reached * 100:.0f} %"
    return f"{head} · {_ci(s['sigma_f'], 3)} · {_ci(s['after5'], 1)}"


def compact_markdown(cells: list) -> list:
    """One row per experiment and tilt limit; per vehicle and law: reached (share of seeds) ·
    mean sigma_f over [25, 40] s ± 95 % CI · worst follower's largest slot distance after 5 s."""
    index = {(c.experiment, c.vehicle, c.law, c.tilt_max): c for c in cells}
    present = [v for v in VEHICLES if any(c.vehicle == v for c in cells)]
    head = "| experiment | tilt_max (rad) | " + " | ".join(
        f"{v}: {law}" for v in present for law in LAWS) + " |"
    lines = [head, "|---|---:|" + "---|" * (len(present) * len(LAWS))]
    for exp, tilt in sorted({(c.experiment, c.tilt_max) for c in cells}):
        row = ["no variant (continuous)" if exp.startswith("exp1") and law == "constrained"
               else _cell_text(index.get((exp, v, law, tilt))) for v in present for law in LAWS]
        lines.append(f"| `{exp}` | {tilt:.2f} | " + " | ".join(row) + " |")
    return lines

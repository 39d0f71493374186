#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The estimation study's table (scripts/study_estimation.sh): for every sweep under OUT
(OUT/<experiment>/<vehicle>[_ideal]) one row per cell: the varied values, complete runs out of
seeds, runs with safety events, and mean sigma_f with its 95 % confidence interval over the
complete runs (and over the valid ones, without a flip, ground impact or collision, when some
run had an event; a sweep.json from before that rule: without any event). Prints Markdown;
--out FILE writes it too."""
import argparse
import sys
from pathlib import Path

from mjfanalysis.io import axis_value, load_sweep


def _label(value) -> str:
    value = axis_value(value)
    if isinstance(value, dict):
        return ", ".join(f"{k}={v}" for k, v in value.items())
    return str(value)


def _interval(metrics: dict | None, key: str = "sigma_f_mean") -> str:
    m = (metrics or {}).get(key)
    if not m or m.get("mean") is None:
        return "n/a"
    low, high = m["ci95"]
    if low is None or m.get("n", 0) < 2:
        return f"{m['mean']:.3g}"
    return f"{m['mean']:.3g} [{low:.3g}, {high:.3g}]"


def table(out: Path) -> str:
    lines = []
    for sweep_json in sorted(out.glob("*/*/sweep.json")):
        sweep = load_sweep(sweep_json.parent)
        rel = sweep_json.parent.relative_to(out)
        lines.append(f"\n### {rel} ({sweep.seeds} seeds per cell"
                     f"{'' if sweep.complete else '; INCOMPLETE'})\n")
        keys = sweep.varied
        lines.append("| " + " | ".join(keys) + " | complete | with events | sigma_f_mean [95 % CI] "
                     "| valid runs |")
        lines.append("|" + "---|" * (len(keys) + 4))
        for cell in sweep.cells:
            events = cell.get("runs_with_safety_events", 0)
            free = _interval(cell.get("metrics_valid", cell.get("metrics_event_free"))) \
                if events else "="
            lines.append("| " + " | ".join(_label(cell[k]) for k in keys) +
                         f" | {cell['complete_runs']}/{cell['seeds']} | {events} | "
                         f"{_interval(cell.get('metrics'))} | {free} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path, help="the study folder (scripts/study_estimation.sh)")
    parser.add_argument("--out", dest="file", type=Path, help="also write the table here")
    args = parser.parse_args(argv)
    if not list(args.out.glob("*/*/sweep.json")):
        print(f"estimation_study: no sweeps under {args.out}", file=sys.stderr)
        return 1
    text = table(args.out)
    print(text)
    if args.file:
        args.file.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

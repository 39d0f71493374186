#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Before/after table of an engine change: the same runs (dev/engine_runs.sh) on two engines.

    dev/engine_table.py BEFORE_DIR AFTER_DIR [--out table.md]

One row per run and headline metric of summary.json; the relative change, with every change over
2 % marked (docs/RESULTS.md says why each one moved).
"""
import argparse
import json
import math
import pathlib
import sys

METRICS = [
    ("sigma_f_mean", "sigma_f (window mean)"),
    ("sigma_f_final", "sigma_f (final)"),
    ("max_final_slot_error_m", "max final slot error, m"),
    ("min_separation_m", "min separation, m"),
    ("max_follower_tilt_deg_in_window", "max tilt in window, deg"),
]
THRESHOLD = 0.02


def load(run_dir):
    summary = json.loads((run_dir / "summary.json").read_text())
    return summary


def change(before, after):
    if before is None or after is None:
        return None
    if before == after:
        return 0.0
    scale = max(abs(before), 1e-12)
    return (after - before) / scale


def fmt(value):
    if value is None:
        return "n/a"
    return f"{value:.4g}"


def rows(before_dir, after_dir):
    names = sorted(p.name for p in before_dir.iterdir() if (p / "summary.json").exists())
    for name in names:
        b, a = load(before_dir / name), load(after_dir / name)
        for key, label in METRICS:
            vb, va = b["metrics"].get(key), a["metrics"].get(key)
            yield name, label, vb, va, change(vb, va), b["complete"], a["complete"]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=pathlib.Path)
    parser.add_argument("after", type=pathlib.Path)
    parser.add_argument("--out", type=pathlib.Path)
    args = parser.parse_args(argv)
    vb = json.loads(next(args.before.glob("*/summary.json")).read_text())["versions"]["mujoco"]
    va = json.loads(next(args.after.glob("*/summary.json")).read_text())["versions"]["mujoco"]
    lines = [f"| run | metric | MuJoCo {vb} | MuJoCo {va} | change |", "|---|---|---|---|---|"]
    over = 0
    for name, label, b, a, c, cb, ca in rows(args.before, args.after):
        mark = ""
        if c is not None and abs(c) > THRESHOLD:
            mark = " **>2 %**"
            over += 1
        done = "" if (cb and ca) else " (incomplete)"
        pct = "n/a" if c is None else ("0" if c == 0 else f"{100 * c:+.2g} %")
        lines.append(f"| {name}{done} | {label} | {fmt(b)} | {fmt(a)} | {pct}{mark} |")
    lines.append("")
    lines.append(f"{over} cells changed by more than 2 %.")
    text = "\n".join(lines) + "\n"
    if args.out:
        args.out.write_text(text)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()

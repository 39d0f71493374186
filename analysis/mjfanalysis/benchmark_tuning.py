# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The benchmark's tuning procedure (docs/BENCHMARK.md, "Tuning procedure"): the same budget of
runs for every non-paper law, on a tuning scenario that is not scored.

Per law: a search space of its gains (each log-uniform in [default / 10, default x 10]); the
budget is `points` points (the plugin's defaults first, then seeded random ones) and `steps`
coordinate steps about the best point so far (gain g = step // 2 mod the number of gains,
times 2 on even steps and / 2 on odd ones). A point's score is the board's (RMS slot error in
the window); a failed run scores +infinity; ties keep the earlier point.
"""

from __future__ import annotations

import json
import math
import random
import subprocess
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from . import benchmark_metrics as bm

REPO = Path(__file__).resolve().parents[2]
TUNING_SCENARIO = REPO / "experiments" / "benchmark" / "tuning" / "tune_circle.toml"

# Each law's gains and their plugin defaults (plugins/formation/README.md). A gain given as a
# list of names is one vector attribute (super_twisting's K = [k1, k2]). Exponents, switches
# and initial values (terminal_smc's p, q; adaptive_tracking's d0) are not gains.
SEARCH_SPACE = {
    "consensus_linear": {"kp": 1.0, "kv": 2.0},
    "vs_tracking": {"alpha": 2.0, "beta": 1.5, "gamma": 1.0},
    "super_twisting": {"k1": 3.0, "k2": 1.0, "lambda": 1.5, "alpha": 0.5},
    "adaptive_tracking": {"tau": 0.02, "phi": 0.05, "kappa": 0.1},
    "observer_tracking": {"k": 1.0, "gamma": 1.0},
    "terminal_smc": {"beta": 1.0, "rho": 1.5},
}
VECTOR_GAINS = {"super_twisting": {"k": ("k1", "k2")}}


@dataclass
class Budget:
    points: int = 8  # the defaults, then points - 1 seeded random points
    steps: int = 32  # coordinate steps
    seed: int = 1


def formation_table(law: str, gains: dict) -> str:
    """The inline [formation] table of `law` at `gains` (17 significant digits)."""
    parts = [f'plugin="{law}"']
    vectors = VECTOR_GAINS.get(law, {})
    in_vector = {g for names in vectors.values() for g in names}
    for key, names in vectors.items():
        parts.append(f"{key}=[" + ", ".join(f"{gains[n]:.17g}" for n in names) + "]")
    parts += [f"{k}={v:.17g}" for k, v in gains.items() if k not in in_vector]
    return "{" + ", ".join(parts) + "}"


def random_points(defaults: dict, budget: Budget) -> list:
    """The defaults, then points - 1 log-uniform points in [d / 10, 10 d] per gain."""
    rng = random.Random(budget.seed)
    points = [dict(defaults)]
    for _ in range(budget.points - 1):
        points.append({k: d * 10.0 ** rng.uniform(-1.0, 1.0) for k, d in defaults.items()})
    return points


def coordinate_step(best: dict, step: int) -> dict:
    """Step `step` about `best`: gain step // 2 (mod the count) times 2 (even) or / 2 (odd)."""
    names = list(best)
    point = dict(best)
    name = names[(step // 2) % len(names)]
    point[name] *= 2.0 if step % 2 == 0 else 0.5
    return point


def score(metrics: dict) -> float:
    """The objective: the RMS slot error, +infinity for a failed run."""
    if metrics.get("failed"):
        return math.inf
    value = metrics.get("rms_slot_error_m")
    return value if value is not None and math.isfinite(value) else math.inf


def fly(mjformation: str, law: str, gains: dict, out: Path, sets: list) -> float:
    """One tuning run at `gains` into `out`; its score."""
    cmd = [mjformation, "run", str(TUNING_SCENARIO), "--out", str(out), "--overwrite",
           "--no-render", "-q", "--set", f"formation={formation_table(law, gains)}",
           "--set", "run.seed=1"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, capture_output=True, text=True)
    if not (out / "summary.json").is_file():
        return math.inf  # refused at load (a gain outside the law's range): not a valid point
    return score(bm.run_metrics(out))


def tune_law(mjformation: str, law: str, out: Path, budget: Budget, jobs: int = 2,
             sets: list | None = None) -> dict:
    """Runs the procedure for one law; returns its trace and the chosen gains."""
    sets = sets or []
    trace = []
    points = random_points(SEARCH_SPACE[law], budget)
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        scores = list(pool.map(lambda ip: fly(mjformation, law, ip[1], out / f"p{ip[0]:02d}",
                                              sets), enumerate(points)))
    trace += [{"gains": p, "score": s} for p, s in zip(points, scores)]
    best = min(range(len(trace)), key=lambda i: (trace[i]["score"], i))
    for step in range(budget.steps):
        point = coordinate_step(trace[best]["gains"], step)
        s = fly(mjformation, law, point, out / f"c{step:02d}", sets)
        trace.append({"gains": point, "score": s})
        if s < trace[best]["score"]:
            best = len(trace) - 1
    return {"law": law, "runs": len(trace), "best": trace[best],
            "formation": formation_table(law, trace[best]["gains"]), "trace": trace}


def write_result(result: dict, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(result, indent=1, allow_nan=True) + "\n")

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""analysis/mjfanalysis/estimation_figure.py: from a small synthetic run directory with the
estimate columns, from one without them, and (when the runner is built) from a real kf_ins run."""
import json
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from mjfanalysis import estimation_figure as EF
from mjfanalysis.io import load_run
from mjfanalysis.report import write_report

from conftest import make_run

ROOT = Path(__file__).resolve().parents[2]
RUNNER = Path(os.environ.get("MJF_BUILD_DIR", ROOT / "build")) / "runner" / "mjformation"


def add_estimate(run_dir: Path, sigma=0.3, seed=1):
    """Appends uav<i>_{px..vz}_est, _std and uav<i>_nees to the fixture's timeseries.csv:
    the truth plus N(0, sigma^2) errors, so the NEES is chi-square(6) by construction."""
    path = run_dir / "timeseries.csv"
    lines = path.read_text().splitlines()
    names = lines[0].split(",")
    data = np.array([[float(c) if c else math.nan for c in row.split(",")] for row in lines[1:]])
    rng = np.random.default_rng(seed)
    n = 1 + max(int(c[3:c.index("_")]) for c in names if c.startswith("uav"))
    extra_names, extra = [], []
    for i in range(n):
        errs = rng.normal(0.0, sigma, size=(len(data), 6))
        for k, c in enumerate(("px", "py", "pz", "vx", "vy", "vz")):
            extra_names.append(f"uav{i}_{c}_est")
            extra.append(data[:, names.index(f"uav{i}_{c}")] + errs[:, k])
        for c in ("px", "py", "pz", "vx", "vy", "vz"):
            extra_names.append(f"uav{i}_{c}_std")
            extra.append(np.full(len(data), sigma))
        extra_names.append(f"uav{i}_nees")
        extra.append((errs**2).sum(axis=1) / sigma**2)
    out = np.column_stack([data] + extra)
    with open(path, "w") as f:
        f.write(",".join(names + extra_names) + "\n")
        for row in out:
            f.write(",".join("" if not math.isfinite(x) else f"{x:.9g}" for x in row) + "\n")


def test_synthetic_run_gets_the_figure(tmp_path):
    d, _, _ = make_run(tmp_path / "results", "exp2", exp=2, t_end=10.0)
    add_estimate(d)
    run = load_run(d)
    assert EF.estimated_vehicles(run.timeseries) == list(range(7))
    out = EF.figure(run, tmp_path / "fig" / EF.FIGURE_NAME)
    assert out is not None and out.stat().st_size > 10000
    # Deterministic: the same data, the same bytes.
    again = EF.figure(load_run(d), tmp_path / "fig2" / EF.FIGURE_NAME)
    assert again.read_bytes() == out.read_bytes()


def test_no_estimate_no_figure(tmp_path):
    d, _, _ = make_run(tmp_path / "results", "exp2", exp=2, t_end=5.0)
    assert EF.figure(load_run(d), tmp_path / EF.FIGURE_NAME) is None
    assert not (tmp_path / EF.FIGURE_NAME).exists()


def test_report_draws_it_only_for_estimated_runs(tmp_path):
    d, _, _ = make_run(tmp_path / "results", "exp2", exp=2, t_end=10.0)
    add_estimate(d)
    make_run(tmp_path / "results", "exp3", exp=3, t_end=10.0)
    md = write_report(tmp_path / "results", tmp_path / "report").read_text()
    assert "figures/exp2/estimation.png" in md
    assert "figures/exp3/estimation.png" not in md
    assert (tmp_path / "report" / "figures" / "exp2" / "estimation.png").exists()


def test_wilson_hilferty_band_for_six():
    lo, hi = EF.single_band(None)
    assert lo == pytest.approx(1.237, abs=0.04)  # exact 1.2373
    assert hi == pytest.approx(14.449, abs=0.02)  # exact 14.4494
    assert EF.single_band({"estimation": {"nees_band_95_single": [1.2373, 14.4494]}}) == (
        1.2373, 14.4494)


@pytest.mark.skipif(not RUNNER.exists(), reason="the runner is not built")
def test_real_kf_ins_run(tmp_path):
    out = tmp_path / "kf"
    cmd = [str(RUNNER), "run", str(ROOT / "experiments" / "exp2.toml"), "--out", str(out),
           "--no-render", "--set", "run.duration=4.0", "--set", "run.metric_window=[2.0, 4.0]",
           "--set", 'sensors={preset="consumer_gnss"}', "--set", 'estimator={plugin="kf_ins"}']
    subprocess.run(cmd, check=True, capture_output=True, timeout=300)
    run = load_run(out)
    est = run.summary["estimation"]
    assert est["plugin"] == "kf_ins"
    assert len(est["vehicles"]) == run.summary["n_followers"] + 1
    png = EF.figure(run, tmp_path / EF.FIGURE_NAME)
    assert png is not None and png.stat().st_size > 10000
    json.dumps(est)  # plain JSON, no NaN

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjformation.sweep: the CLI's sweep in-process, with the same tables."""

import json
import subprocess

import pytest
from conftest import short

import mjformation


def test_sweep_gives_the_cli_tables_and_a_frame(cli, exp2, tmp_path):
    fixed = short(1.0)
    mjf = mjformation.sweep(exp2, vary={"formation.q": [1.5, 4.5]}, seeds=2, jobs=2, set=fixed,
                            out=tmp_path / "py")
    args = [cli, "sweep", str(exp2), "--vary", "formation.q=1.5,4.5", "--seeds", "2", "--jobs",
            "2", "--no-render", "--out", str(tmp_path / "cli")]
    for k, v in fixed.items():
        args += ["--set", f"{k}={json.dumps(v)}"]
    assert subprocess.run(args, capture_output=True).returncode == 0
    for name in ("sweep.csv", "sweep.json", "sweep_runs.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    assert mjf.complete and len(mjf.cells) == 2 and len(mjf.runs) == 4
    assert all(r.complete for r in mjf.load_runs())  # each run as a Run (the one loader)
    pd = pytest.importorskip("pandas")
    frame = mjf.frame()
    assert isinstance(frame, pd.DataFrame) and list(frame["formation.q"]) == [1.5, 4.5]
    assert (frame["sigma_f_mean_ci95_low"] <= frame["sigma_f_mean_mean"]).all()
    # The sweep plot (mjfanalysis.sweep_plot): per cell the mean against the varied parameter;
    # Exp 2 has no random input, so its seeds agree and no cell has an interval to draw
    import matplotlib

    matplotlib.use("Agg")
    ax = mjf.plot("sigma_f_mean")
    line = ax.lines[0]
    assert list(line.get_xdata()) == [1.5, 4.5]
    assert list(line.get_ydata()) == list(frame["sigma_f_mean_mean"])
    assert ax.get_xlabel() == "formation.q" and not ax.containers


def test_sweep_with_a_bad_override_raises_value_error(exp2, tmp_path):
    with pytest.raises(ValueError, match=r"--set formation\.q=-1(\.0)?: \[formation\] q"):
        mjformation.sweep(exp2, vary={"formation.q": [1.0]}, set={"formation.q": -1.0},
                          out=tmp_path / "s")


def test_a_python_law_sweeps_on_the_worker_threads(exp2, tmp_path):
    from consensus_law import consensus

    sw = mjformation.sweep(exp2, vary={"formation.period": [0.01, 0.05]}, jobs=2, set=short(1.0),
                           formation=mjformation.FormationLaw(consensus), out=tmp_path / "s")
    assert sw.complete and len(sw.runs) == 2
    for run, period in zip(sw.load_runs(), ("0.01", "0.05")):
        assert run.summary["plugins"]["formation"]["attributes"] == {
            "law": "consensus_law.consensus", "period": period}
        assert run.summary["plugin_report"]["python_calls"] == 1 + round(1.0 / float(period))

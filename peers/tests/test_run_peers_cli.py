# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""run_peers.py as a user meets it: one-line refusals before anything is installed, and a report
that states only what its invocation measured, written into the output folder unless --doc."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

PEERS = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(PEERS))

from peerlib import params as P  # noqa: E402


def refusal(*args):
    """stderr of run_peers.py refusing its arguments: one line, no traceback, exit status 1."""
    done = subprocess.run([sys.executable, str(PEERS / "run_peers.py"), *args],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "Traceback" not in done.stderr and done.stderr.count("\n") == 1, done.stderr
    return done.stderr


def fake_runner(tmp_path):
    runner = tmp_path / "mjformation"
    runner.write_text("#!/bin/sh\necho 'mjformation 0 (MuJoCo 4.0.1, plugin ABI 3)'\n")
    runner.chmod(0o755)
    return str(runner)


def test_refuses_bad_arguments_in_one_line(tmp_path):
    out = ["--out", str(tmp_path / "out")]
    runner = ["--binary", fake_runner(tmp_path)]
    assert "--sizes: 'abc' is not a number of vehicles" in refusal(*out, *runner, "--sizes", "1,abc")
    assert "--peers: unknown peer 'gazebo'; the harness knows rotorpy" in refusal(
        *out, *runner, "--peers", "rotorpy,gazebo")
    missing = tmp_path / "no" / "mjformation"
    assert f"--binary no runner at {missing}; build it" in refusal(*out, "--binary", str(missing))
    assert "--build /nowhere: no runner at /nowhere/runner/mjformation" in refusal(*out, "--build", "/nowhere")
    assert "--out /proc/peers: cannot write there" in refusal("--out", "/proc/peers", *runner)


def test_report_only_refuses_missing_or_garbled_results(tmp_path):
    assert f"{tmp_path / 'results.json'}: no results to report; run the harness" in refusal(
        "--report-only", "--out", str(tmp_path))
    (tmp_path / "results.json").write_text('{"speed": [\n')
    assert "results.json: line 2: not valid JSON" in refusal("--report-only", "--out", str(tmp_path))
    (tmp_path / "results.json").write_text('{"speed": []}')
    assert "not a results file of this harness (no 'dynamics')" in refusal(
        "--report-only", "--out", str(tmp_path))


def skipped_everything():
    """results.json of `--skip-speed --skip-dynamics` (only the installs ran)."""
    machine = {"cpu": "cpu", "nproc": 2, "python": "3.11", "os": "Debian", "loadavg": [1.0, 1.0, 1.0],
               "loadavg_end": [1.0, 1.0, 1.0]}
    return {"started": "2026-01-01T00:00:00+00:00", "command": "peers/run_peers.py --skip-speed --skip-dynamics",
            "machine": machine, "binary": str(PEERS.parent / "build/runner/mjformation"),
            "reference": P.REFERENCE, "derived": P.derived(), "unmatched": P.unmatched(),
            "args": {"duration": 40.0, "wall_budget": 120.0}, "install": {}, "speed": [], "dynamics": {},
            "mjformation_version": "mjformation 0.1.0 (MuJoCo 4.0.1, plugin ABI 3)"}


def test_a_skipped_tier_is_reported_as_not_run_into_the_output_folder(tmp_path):
    (tmp_path / "results.json").write_text(json.dumps(skipped_everything()))
    tracked = PEERS.parent / "docs" / "PEERS.md"
    before = tracked.read_bytes()
    done = subprocess.run([sys.executable, str(PEERS / "run_peers.py"), "--report-only", "--out", str(tmp_path)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert tracked.read_bytes() == before  # the tracked report only with --doc
    text = (tmp_path / "PEERS.md").read_text()
    assert "did not run in this invocation (`--skip-dynamics`)" in text
    assert "Speed: not measured in this invocation (`--skip-speed`)" in text
    for claim in ("agree to rounding", "no peer parted", "MuJoCo ?", "did not run: None", "Accelerations agree",
                  "What the differences come from"):
        assert claim not in text, claim
    assert "runner `build/runner/mjformation`" in text  # inside the checkout: written relative to it


def test_the_dynamics_summary_quotes_the_measured_differences():
    import report
    acc = {"level_at_rest": {"lin": [0.0, 0.0, 0.0], "ang": [0.0, 0.0, 0.0]}}
    results = {"dynamics": {
        "mjformation": {"jobs": [{"job": {"kind": "dynamics"}, "accel": acc}]},
        "rotorpy": {"jobs": [{"job": {"kind": "dynamics", "bare": True},
                              "accel": {"level_at_rest": {"lin": [0.0, 0.0, 2e-6], "ang": [0.0, 0.0, 0.0]}}}]}}}
    text = report.dynamics_summary(results, None)
    assert "differ from mjformation's by at most 2.0e-06 m/s^2 and 0.0e+00 rad/s^2" in text
    assert "tier (b) has no open-loop result" in text

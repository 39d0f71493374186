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


def test_refuses_bad_selections_in_one_line(tmp_path):
    out = ["--out", str(tmp_path / "out")]
    runner = ["--binary", fake_runner(tmp_path)]
    assert "--workloads: unknown workload 'W3'; the harness knows W1, W2" in refusal(*out, *runner, "--workloads", "W1,W3")
    assert "--sizes: no size given" in refusal(*out, *runner, "--sizes", ",")
    assert "--doc-section: names no report to write into; add --doc" in refusal(*out, *runner, "--doc-section")
    assert "--warmup-periods: 0 is below 1" in refusal(*out, *runner, "--warmup-periods", "0")


def test_sizes_and_workloads_are_taken_in_the_order_given():
    import run_peers
    assert run_peers.checked_sizes("1000, 7,") == [1000, 7]
    assert run_peers.checked_workloads("W2,W1") == ["W2", "W1"]


def cell(sim, n, wall, workload="W1", controller="own", **extra):
    return dict({"sim": sim, "workload": workload, "n": n, "controller": controller,
                 "runs": [{"sim_s": 10.0, "wall_s": wall, "physics_steps": 10000}]}, **extra)


def test_merge_keeps_the_cells_not_measured_again():
    import run_peers
    old = dict(skipped_everything(), speed=[cell("mjformation", 7, 1.0, controller="hover"), cell("crazyflow", 7, 2.0),
                                            cell("crazyflow", 1000, 9.0)],
               dynamics={"mjformation": {"jobs": []}}, install={"rotorpy": {"ok": True}})
    new = dict(skipped_everything(), started="2026-01-02T00:00:00+00:00", command="peers/run_peers.py --sizes 1000",
               speed=[cell("crazyflow", 1000, 3.0), cell("mjformation", 1000, 4.0, controller="hover")],
               install={"crazyflow": {"ok": True}})
    merged = run_peers.merge_results(old, new)
    assert [(c["sim"], c["n"], c["runs"][0]["wall_s"]) for c in merged["speed"]] == [
        ("mjformation", 7, 1.0), ("crazyflow", 7, 2.0), ("crazyflow", 1000, 3.0), ("mjformation", 1000, 4.0)]
    assert merged["dynamics"] == old["dynamics"] and merged["started"] == old["started"]
    assert set(merged["install"]) == {"rotorpy", "crazyflow"}
    assert [i["command"] for i in merged["invocations"]] == [old["command"], new["command"]]
    assert run_peers.merge_results(None, new) is new


DOC = "# Report\n\n## Speed: W1 and W2\n\nrows of N = 1, 7, 49\n\n## Dynamics cross-check\n\ntiers\n"


def test_a_section_is_placed_before_the_dynamics_then_replaced_in_place():
    import report
    once = report.splice(DOC, [1000], "## Speed at N = 1000\n\nfirst")
    begin, end = report.section_markers([1000])
    assert once.startswith(DOC.split("## Dynamics")[0] + begin)
    assert once.endswith(end + "\n\n## Dynamics cross-check\n\ntiers\n")
    twice = report.splice(once, [1000], "## Speed at N = 1000\n\nsecond")
    assert "first" not in twice and twice == once.replace("first", "second")
    assert report.splice("# Other\n", [1000], "body") == f"# Other\n\n{begin}\nbody\n{end}\n"


def test_the_section_states_duration_overrides_load_and_the_peers_not_run():
    import report
    results = dict(skipped_everything(), speed=[
        cell("mjformation", 7, 1.0), cell("crazyflow", 7, 2.0),
        cell("mjformation", 1000, 20.0, sets=['vehicles.rotor_model="wrench"'], duration=10.0, load=[9.5, 9.0, 8.0],
             measured="2026-01-01T00:05:00+00:00"),
        cell("crazyflow", 1000, 10.0, duration=10.0, load=[12.25, 9.0, 8.0], warmup_periods=2,
             measured="2026-01-01T00:06:00+00:00"),
        cell("crazyflow", 1000, 10.0, workload="W2", duration=10.0)])
    text = report.section(results, [1000])
    assert text.startswith("## Speed at N = 1000\n")
    assert "Simulated seconds asked for per run: 10.0 " in text
    assert "and 9.5, 12.2 (1-min, one sample per cell" in text
    assert "`--set vehicles.rotor_model=\"wrench\"`" in text
    assert "not run at this size: RotorPy, PyFlyt" in text
    assert "first 2 control periods are timed apart" in text
    assert "- mjformation against Crazyflow: N = 1000: 0.500x (below 1" in text
    assert "W2 at N = 1000: the slots lie on a circle of 31.8 m around the leader turning at 0.00987 rad/s " \
           "(0.314 m/s relative to it" in text and "start on a ring of 30.9 m" in text
    assert "| 7 |" not in text  # the other sizes stay in their own table


def test_merge_and_section_from_a_run_of_the_runner(tmp_path):
    """One tiny mjformation-only invocation with --merge --doc-section: the earlier results and the
    rest of the report are kept, the new size's cell is added and its section spliced in."""
    import os
    cli = os.environ.get("MJF_CLI")
    if not cli:
        pytest.skip("MJF_CLI not set: needs the runner")
    old = dict(skipped_everything(), speed=[cell("mjformation", 7, 1.0, controller="hover")])
    (tmp_path / "results.json").write_text(json.dumps(old))
    doc = tmp_path / "DOC.md"
    doc.write_text(DOC)
    done = subprocess.run([sys.executable, str(PEERS / "run_peers.py"), "--binary", cli, "--peers", "", "--sizes", "3",
                           "--workloads", "W1", "--duration", "0.2", "--repeats", "1", "--skip-dynamics",
                           "--batch-worlds", "0", "--merge", "--out", str(tmp_path), "--doc", str(doc), "--doc-section"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    merged = json.loads((tmp_path / "results.json").read_text())
    assert [(c["sim"], c["n"]) for c in merged["speed"]] == [("mjformation", 7), ("mjformation", 3)]
    assert merged["speed"][1]["duration"] == 0.2 and len(merged["invocations"]) == 2
    text = doc.read_text()
    assert text.startswith(DOC.split("## Dynamics")[0]) and text.endswith("## Dynamics cross-check\n\ntiers\n")
    assert "## Speed at N = 3" in text and "| mjformation | W1 | 3 | hover guidance |" in text

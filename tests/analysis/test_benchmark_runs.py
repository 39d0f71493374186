# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The benchmark's flying loop (mjfanalysis.benchmark) with a stand-in for `mjformation run`
that writes a tiny run directory and logs its calls: resume, interrupted runs, the command
line of a cell."""
import json
import sys
from pathlib import Path

import pytest

from mjfanalysis import benchmark as b

# Writes --out as a two-sample run of one follower whose slot error is the seed (in m); the
# law "crashes" flips; a run of the law "stop" is interrupted; the law "central_only" is refused
# as the runner refuses a law without a per-agent version in a per-agent scenario. Every call is
# logged.
FAKE = r'''
import json, sys
from pathlib import Path
args = sys.argv[1:]
out = Path(args[args.index("--out") + 1])
sets = [args[i + 1] for i, a in enumerate(args) if a == "--set"]
seed = int(next(s for s in sets if s.startswith("run.seed=")).split("=")[1])
law = next(s for s in sets if s.startswith("formation=")).split('"')[1]
with open(Path(__file__).with_name("calls.log"), "a") as f:
    f.write(" ".join(args) + "\n")
if law == "central_only":
    sys.exit("b13.toml:42: [formation] plugin: 'central_only' has no per-agent version "
             "('central_only_agent') for [execution] mode = \"per_agent\"")
out.mkdir(parents=True, exist_ok=True)
rows = "\n".join(f"{t},0,0,,,0,0,{seed},0,1,0,0,0" for t in (0.0, 1.0))
(out / "timeseries.csv").write_text(
    "t,uav0_px,uav0_py,uav0_ax_cmd,uav0_ay_cmd,uav0_slot_x,uav0_slot_y,"
    "uav1_px,uav1_py,uav1_ax_cmd,uav1_ay_cmd,uav1_slot_x,uav1_slot_y\n" + rows + "\n")
s = {"complete": True, "metrics": {"sigma_f_window": [0.0, 1.0], "sigma_f_mean": 1.0,
                                   "min_separation_m": 3.0}}
if law == "crashes":
    s["events"] = {"count": 1, "by_kind": {"flip": 1}, "list": []}
if law == "stop":
    s.update(complete=False, interrupted_by_signal=2)
(out / "summary.json").write_text(json.dumps(s))
'''


@pytest.fixture
def fake(tmp_path):
    script = tmp_path / "fake_mjformation.py"
    script.write_text(FAKE)
    runner = tmp_path / "mjformation"
    runner.write_text(f"#!/bin/sh\nexec {sys.executable} {script} \"$@\"\n")
    runner.chmod(0o755)
    return runner


def _plan(fake, tmp_path, laws):
    return b.Plan(mjformation=str(fake), laws={law: f'{{plugin="{law}"}}' for law in laws},
                  scenarios=["b01_paper_circle"], seeds=[1, 2], out=tmp_path / "board",
                  sets=["run.duration=1.0"], jobs=2)


def _calls(tmp_path):
    log = tmp_path / "calls.log"
    return log.read_text().splitlines() if log.exists() else []


def test_flies_each_cell_once_and_resumes(fake, tmp_path, capsys):
    plan = _plan(fake, tmp_path, ["good", "crashes"])
    records = b.fly_all(plan)
    assert len(_calls(tmp_path)) == 4
    assert "4/4 runs (0 done before)" in capsys.readouterr().err
    score = {(r["law"], r["seed"]): r["metrics"] for r in records}
    assert score[("good", 2)]["rms_slot_error_m"] == 2.0 and score[("good", 2)]["failed"] is None
    assert score[("crashes", 1)]["failed"] == "safety: 1 flip"
    again = b.fly_all(plan)
    assert len(_calls(tmp_path)) == 4  # nothing flown again
    assert "all 4 runs done before" in capsys.readouterr().err
    assert again == records
    (b.run_dir(plan, "good", "b01_paper_circle", 1) / b.bm.METRICS_FILE).unlink()
    b.fly_all(plan)
    assert len(_calls(tmp_path)) == 5  # only the unscored run


def test_a_law_without_a_per_agent_version_is_not_applicable_and_not_flown_again(fake, tmp_path):
    plan = _plan(fake, tmp_path, ["central_only", "good"])
    records = b.fly_all(plan)
    score = {(r["law"], r["seed"]): r["metrics"] for r in records}
    assert "has no per-agent version" in score[("central_only", 1)]["not_applicable"]
    assert score[("central_only", 2)]["failed"] is None
    assert "not_applicable" not in score[("good", 1)]
    b.fly_all(plan)
    assert len(_calls(tmp_path)) == 4  # resumed: the refused cells are done, not flown again
    board = b.write_board(records, {"seeds": [1, 2]}, tmp_path / "out")
    cell = next(c for c in board["cells"] if c["law"] == "central_only")
    assert cell["mean"] is None and cell["rank"] is None and cell["failed"] is None
    assert "not applicable (central_only has no per-agent version)" in (
        tmp_path / "out" / "leaderboard.md").read_text()


def test_an_interrupted_run_stops_the_board_unscored(fake, tmp_path):
    plan = _plan(fake, tmp_path, ["stop"])
    plan.jobs = 1
    with pytest.raises(SystemExit, match="the same command resumes"):
        b.fly_all(plan)
    assert len(_calls(tmp_path)) == 1  # the second seed was never started
    assert b.done_metrics(b.run_dir(plan, "stop", "b01_paper_circle", 1)) is None


def test_cell_command_line(tmp_path):
    plan = b.Plan(mjformation="mjf", laws={"x": '{plugin="x", k=1.0}'}, scenarios=["s"],
                  seeds=[3], out=Path("o"), sets=["run.duration=2.0"], plugin_path=["p"])
    cmd = b.command(plan, "x", "s", 3)
    assert cmd[:3] == ["mjf", "run", str(b.SCENARIO_DIR / "s.toml")]
    assert cmd[3:5] == ["--out", "o/runs/x/s/seed3"]
    text = " ".join(cmd)
    assert '--set formation={plugin="x", k=1.0} --set run.seed=3 --set run.duration=2.0' in text
    assert text.endswith("--plugin-path p")
    assert set(b.known_laws()) >= {"smc_discrete", "vs_tracking", "terminal_smc"}
    assert "b01_paper_circle" in b.known_scenarios() and "laws" not in b.known_scenarios()
    assert json.dumps(b.pick("b01_paper_circle", b.known_scenarios(), "scenario"))
    with pytest.raises(SystemExit, match="unknown law 'nope'"):
        b.pick("nope", b.known_laws(), "law")


def test_python_law_cell_runs_through_mjformation_run():
    assert b.python_law("/laws/mine.py:my_law") and b.python_law("mine.py:law2")
    assert not b.python_law("smc_discrete") and not b.python_law("mine.py") \
        and not b.python_law("mine.txt:law") and not b.python_law("mine.py:not-a-name")
    plan = b.Plan(mjformation="build/runner/mjformation", laws={"my_law": "/laws/mine.py:my_law"},
                  scenarios=["s"], seeds=[2], out=Path("o"), sets=["run.duration=2.0"],
                  plugin_path=["p"])
    cmd = b.command(plan, "my_law", "s", 2)
    assert cmd[:6] == [sys.executable, str(b.PYTHON_LAW_RUNNER), "/laws/mine.py:my_law",
                       str(b.SCENARIO_DIR / "s.toml"), "o/runs/my_law/s/seed2", "2"]
    assert " ".join(cmd[6:]) == ("--mjformation build/runner/mjformation "
                                 "--set run.duration=2.0 --plugin-path p")


def test_the_folder_is_claimed_before_anything_is_flown(tmp_path):
    new = tmp_path / "new"
    b.claim_out(new)
    assert (new / b.MARKER).is_file()
    (new / "leaderboard.md").write_text("an earlier board")
    b.claim_out(new)  # the benchmark's own folder: resumed
    users = tmp_path / "users"
    users.mkdir()
    (users / "leaderboard.md").write_text("notes")
    with pytest.raises(SystemExit, match=r"users: exists, is not empty \(leaderboard.md\) and is "
                       r"not a benchmark folder .*would replace leaderboard.md there.*--overwrite"):
        b.claim_out(users)
    assert [p.name for p in users.iterdir()] == ["leaderboard.md"]
    b.claim_out(users, overwrite=True)
    assert (users / b.MARKER).is_file() and (users / "leaderboard.md").read_text() == "notes"
    (tmp_path / "file").write_text("mine")
    with pytest.raises(SystemExit, match="file: is a file, not a folder"):
        b.claim_out(tmp_path / "file", overwrite=True)


SCRIPT = Path(__file__).resolve().parents[2] / "analysis" / "benchmark.py"


def _benchmark(fake, *args):
    """analysis/benchmark.py as `mjformation benchmark` starts it (benchmark_cli.cc)."""
    import os
    import subprocess
    env = dict(os.environ, PYTHONPATH=str(SCRIPT.parent))
    return subprocess.run([sys.executable, str(SCRIPT), "--mjformation", str(fake),
                           "--scenarios", "b01_paper_circle", "--laws", "smc_discrete", *args],
                          capture_output=True, text=True, env=env)


def test_a_users_folder_is_refused_before_anything_is_flown(fake, tmp_path):
    out = tmp_path / "d"
    out.mkdir()
    (out / "leaderboard.md").write_text("notes\n")
    done = _benchmark(fake, "--seeds", "1", "--out", str(out))
    assert done.returncode == 1
    assert "is not a benchmark folder" in done.stderr and "--overwrite" in done.stderr
    assert sorted(p.name for p in out.iterdir()) == ["leaderboard.md"]
    assert (out / "leaderboard.md").read_text() == "notes\n"
    assert _calls(tmp_path) == []
    done = _benchmark(fake, "--seeds", "1", "--out", str(out), "--overwrite")
    assert done.returncode == 0, done.stderr
    assert len(_calls(tmp_path)) == 1 and "smc_discrete" in (out / "leaderboard.md").read_text()


@pytest.mark.parametrize("option, value, takes", [
    ("--seeds", "0", "at least 1"), ("--seeds", "-2", "at least 1"),
    ("--jobs", "0", "at least 1"), ("--band", "-1", "above 0"), ("--band", "nan", "above 0")])
def test_options_out_of_range_are_refused_naming_them(fake, tmp_path, option, value, takes):
    args = ["--seeds", "1", "--out", str(tmp_path / "board"), option, value]
    done = _benchmark(fake, *args)
    assert done.returncode == 2
    assert f"argument {option}: takes" in done.stderr and takes in done.stderr, done.stderr
    assert not (tmp_path / "board").exists() and _calls(tmp_path) == []

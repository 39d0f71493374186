# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Ctrl-C during mjformation.run, and runs on two Python threads (the GIL released)."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
from conftest import short

import mjformation

INTERRUPTED = textwrap.dedent("""
    import os, signal, sys, threading, json
    import mjformation
    threading.Timer(float(sys.argv[3]), lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    try:
        # 400 s of flight: far more than the signal's delay, on an idle machine too (40 s of
        # Exp 2 can finish in under a second)
        mjformation.run(sys.argv[1], out=sys.argv[2], set={"run.duration": 400.0})
        print("no interrupt")
    except KeyboardInterrupt as e:
        # Python's own Ctrl-C handling is back once the run is over
        print(json.dumps({"raised": str(e),
                          "handler": signal.getsignal(signal.SIGINT) is signal.default_int_handler}))
""")


def assert_a_marked_partial_run(out, signum):
    """A run stopped by `signum` during its 400 s: marked incomplete, named, its rows kept."""
    summary = json.loads((out / "summary.json").read_text())
    assert summary["complete"] is False and summary["interrupted_by_signal"] == signum
    assert summary["error"] == f"interrupted by {signal.Signals(signum).name}"
    assert 0 < summary["sim_time_s"] < 400.0  # stopped before the 400 s run ended
    assert (out / ".mjformation-run").is_file()
    assert len((out / "timeseries.csv").read_text().splitlines()) > 2  # rows before it are kept


def test_keyboard_interrupt_during_run_leaves_a_marked_partial_run(exp2, tmp_path):
    out = tmp_path / "r"
    result = subprocess.run([sys.executable, "-c", INTERRUPTED, str(exp2), str(out), "1.5"],
                            capture_output=True, text=True, env=os.environ, timeout=300)
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout.strip().splitlines()[-1])
    assert "partial run kept" in report["raised"] and report["handler"] is True
    assert_a_marked_partial_run(out, signal.SIGINT)


HUNG_UP = textwrap.dedent("""
    import os, signal, sys, threading, json, warnings
    import mjformation
    threading.Timer(float(sys.argv[3]), lambda: os.kill(os.getpid(), signal.SIGHUP)).start()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mjformation.run(sys.argv[1], out=sys.argv[2], set={"run.duration": 400.0})
    # Python's own disposition (the default: end the process) is back once the run is over
    print(json.dumps({"warned": [str(w.message) for w in caught],
                      "handler": signal.getsignal(signal.SIGHUP) == signal.SIG_DFL}))
""")


def test_hangup_during_run_leaves_a_marked_partial_run(exp2, tmp_path):
    # A closed terminal or a dropped ssh session sends SIGHUP: the rows and the summary are kept.
    out = tmp_path / "r"
    result = subprocess.run([sys.executable, "-c", HUNG_UP, str(exp2), str(out), "1.5"],
                            capture_output=True, text=True, env=os.environ, timeout=300)
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout.strip().splitlines()[-1])
    assert any("interrupted by SIGHUP" in w for w in report["warned"]) and report["handler"]
    assert_a_marked_partial_run(out, signal.SIGHUP)


class Law:
    """A sampled law that notes when (wall clock) each call happened."""

    def __init__(self):
        self.times = []

    def __call__(self, t, states, offsets, graph):
        self.times.append(time.monotonic())
        z = states[1:, [0, 1, 3, 4]] - offsets[:, :4] - states[0, [0, 1, 3, 4]]
        return offsets[:, 4:6] - 0.5 * z[:, :2] - 1.5 * z[:, 2:4]


def test_two_runs_on_two_threads_progress_in_parallel_with_their_solo_bytes(exp2, tmp_path):
    settings = {"a": {**short(8.0)}, "b": {**short(8.0), "formation.shape.radius": 7.0}}
    # Solo runs first
    for name, overrides in settings.items():
        mjformation.run(exp2, set=overrides, out=tmp_path / f"solo_{name}",
                        formation=mjformation.FormationLaw(Law(), period=0.05))
    # Then both at once, each on its own thread
    laws = {name: Law() for name in settings}

    def go(name):
        mjformation.run(exp2, set=settings[name], out=tmp_path / f"thread_{name}",
                        formation=mjformation.FormationLaw(laws[name], period=0.05))

    threads = [threading.Thread(target=go, args=(name,)) for name in settings]
    ticks = 0
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):
        ticks += 1  # the main thread keeps running Python meanwhile
        time.sleep(0.001)
    for t in threads:
        t.join()
    # The two runs' law calls interleave: each ran while the other was under way (with the GIL
    # held through a run, the second would start after the first ended: no call inside). The
    # machine is shared, so how much they overlap varies; that they do is what is checked.
    a, b = np.array(laws["a"].times), np.array(laws["b"].times)
    assert len(a) == len(b) == 161
    assert np.sum((b > a[0]) & (b < a[-1])) >= 5 and np.sum((a > b[0]) & (a < b[-1])) >= 5
    assert ticks > 20
    for name in settings:
        solo = (tmp_path / f"solo_{name}/timeseries.csv").read_bytes()
        assert (tmp_path / f"thread_{name}/timeseries.csv").read_bytes() == solo
    assert solo != (tmp_path / "solo_a/timeseries.csv").read_bytes()  # they are two runs

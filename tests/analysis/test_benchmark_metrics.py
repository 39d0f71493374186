# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The benchmark's metrics (docs/BENCHMARK.md) against values computed by hand on a five-sample
run of two followers."""
import json
import math

import pytest

from mjfanalysis import benchmark_metrics as bm

# t = 0..4 s at 1 Hz, window [1, 4]. Follower 1's slot is the origin, follower 2's is (10, 0).
T = [0.0, 1.0, 2.0, 3.0, 4.0]
P1 = [(3.0, 4.0), (0.0, 2.0), (0.5, 0.0), (2.0, 0.0), (0.0, 0.0)]  # errors 5, 2, 0.5, 2, 0
E2 = [1.0, 1.0, 0.2, 0.2, 0.2]  # follower 2 sits E2 m above its slot
U1 = [(50.0, 0.0), (1.0, 0.0), (-1.0, 0.0), (1.0, 0.0), (-1.0, 0.0)]  # t = 0 outside the window
U2 = [(0.0, 100.0), (0.0, 3.0), (0.0, 3.0), (0.0, 0.0), (0.0, 0.0)]


def _write_run(d, *, complete=True, events=None):
    d.mkdir(parents=True)
    cols = ["t"] + [f"uav{i}_{c}" for i in (0, 1, 2)
                    for c in ("px", "py", "ax_cmd", "ay_cmd", "slot_x", "slot_y")]
    rows = []
    for k, t in enumerate(T):
        leader = [20.0, 0.0, "", "", 20.0, 0.0]
        f1 = [*P1[k], *U1[k], 0.0, 0.0]
        f2 = [10.0, E2[k], *U2[k], 10.0, 0.0]
        rows.append(",".join(str(x) for x in [t, *leader, *f1, *f2]))
    (d / "timeseries.csv").write_text(",".join(cols) + "\n" + "\n".join(rows) + "\n")
    summary = {"complete": complete, "error": None if complete else "non-finite state",
               "metrics": {"sigma_f_window": [1.0, 4.0], "sigma_f_mean": 2.5,
                           "min_separation_m": 7.5}}
    if events:
        summary["events"] = {"count": sum(events.values()), "by_kind": events, "list": []}
    (d / "summary.json").write_text(json.dumps(summary))
    return d


def test_metrics_match_hand_computed_values(tmp_path):
    m = bm.write_run_metrics(_write_run(tmp_path / "run"), band=1.0)
    assert m["sigma_f_mean"] == 2.5 and m["min_separation_m"] == 7.5  # summary.json's own
    # squares in W: follower 1 4 + 0.25 + 4 + 0, follower 2 1 + 0.04 * 3; K N = 8
    assert m["rms_slot_error_m"] == pytest.approx(math.sqrt(9.37 / 8), rel=1e-12)
    # worst error 5, 2, 0.5, 2, 0.2: inside 1 m from t = 4 s on
    assert m["reaching_time_s"] == 4.0
    # |du|: follower 1 2 + 2 + 2, follower 2 0 + 3 + 0; over N (t_b - t_a) = 2 * 3
    assert m["chattering_index"] == pytest.approx(9.0 / 6.0, rel=1e-12)
    # sum ||u||^2 h: follower 1 4, follower 2 18; over N = 2
    assert m["control_effort"] == pytest.approx(11.0, rel=1e-12)
    assert m["failed"] is None and m["safety_events"] == {}
    stored = json.loads((tmp_path / "run" / bm.METRICS_FILE).read_text())
    assert stored["rms_slot_error_m"] == m["rms_slot_error_m"]


def test_reaching_time_depends_on_the_band(tmp_path):
    ts = bm.read_timeseries(_write_run(tmp_path / "run") / "timeseries.csv")
    assert bm.reaching_time(ts, 2.5) == 1.0  # only t = 0 (5 m) is outside
    assert bm.reaching_time(ts, 5.0) == 0.0
    assert bm.reaching_time(ts, 0.1) == math.inf  # the last sample (0.2 m) is outside
    m = bm.run_metrics(tmp_path / "run", band=0.1)
    assert m["reaching_time_s"] is None


def test_a_flip_or_an_incomplete_run_fails_and_a_near_miss_does_not(tmp_path):
    flip = bm.run_metrics(_write_run(tmp_path / "flip", events={"flip": 1, "near_miss": 2}))
    assert flip["failed"] == "safety: 1 flip" and flip["safety_events"] == {"flip": 1}
    near = bm.run_metrics(_write_run(tmp_path / "near", events={"near_miss": 3}))
    assert near["failed"] is None
    cut = bm.run_metrics(_write_run(tmp_path / "cut", complete=False))
    assert cut["failed"].startswith("incomplete")


def test_messages_per_second_counts_the_followers_links_only(tmp_path):
    d = _write_run(tmp_path / "run")
    summary = json.loads((d / "summary.json").read_text())
    assert bm.run_metrics(d)["messages_per_s"] is None  # central mode: no network
    summary["sim_time_s"] = 4.0
    summary["network"] = {"links": [
        {"from": 0, "to": 1, "sent": 1000, "round_messages_sent": 0},  # the leader's: not counted
        {"from": 1, "to": 2, "sent": 400, "round_messages_sent": 40},
        {"from": 2, "to": 1, "sent": 400, "round_messages_sent": 0}]}
    (d / "summary.json").write_text(json.dumps(summary))
    # (400 + 40 + 400) messages / (N = 2 followers x 4 s)
    assert bm.run_metrics(d)["messages_per_s"] == pytest.approx(105.0, rel=1e-12)

# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""A recorded run written as MCAP (mjfanalysis.mcap_export) reads back with the `mcap` package:
every channel is there, with Foxglove's schema names, and the poses are timeseries.csv's."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest
from mcap import reader as mcap_reader  # pinned in requirements.txt

from mjfanalysis.io import read_timeseries_csv
from mjfanalysis.mcap_export import TOPICS, main, quaternion_zyx, write_mcap

DURATION = 2.0


@pytest.fixture(scope="module")
def recorded(cli, exp2, tmp_path_factory):
    """Exp 2 for 2 s, with a near-miss distance that its 1.5 m start ring falls inside (events)."""
    out = tmp_path_factory.mktemp("mcap") / "exp2"
    args = [cli, "run", str(exp2), "--out", str(out), "--quiet", "--no-render",
            "--set", f"run.duration={DURATION}", "--set", f"run.metric_window=[0.0, {DURATION}]",
            "--set", "safety.near_miss_m=2.0"]
    result = subprocess.run(args, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    return out


def read(path):
    """{topic: [(log_time ns, message dict)]}, the schema of each topic, metadata, attachments."""
    with open(path, "rb") as f:
        reader = mcap_reader.make_reader(f)
        messages, schemas = {}, {}
        for schema, channel, message in reader.iter_messages():
            assert channel.message_encoding == "json" and schema.encoding == "jsonschema"
            schemas[channel.topic] = schema.name
            messages.setdefault(channel.topic, []).append((message.log_time,
                                                           json.loads(message.data)))
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
        attachments = {a.name: a.data for a in reader.iter_attachments()}
    return messages, schemas, metadata, attachments


def test_every_channel_is_present_with_foxglove_schemas(recorded, tmp_path):
    path = write_mcap(recorded, tmp_path / "exp2.mcap")
    messages, schemas, metadata, attachments = read(path)
    assert schemas == TOPICS
    rows = len(read_timeseries_csv(recorded / "timeseries.csv")["t"])
    for topic in TOPICS:
        if topic != "/events":
            assert len(messages[topic]) == rows, topic
    summary = json.loads((recorded / "summary.json").read_text())
    assert json.loads(metadata["summary"]["summary.json"]) == summary
    assert attachments["config.toml"] == (recorded / "config.toml").read_bytes()
    assert attachments["scene.xml"] == (recorded / "scene.xml").read_bytes()


def test_poses_equal_the_timeseries(recorded, tmp_path):
    messages, _, _, _ = read(write_mcap(recorded, tmp_path / "exp2.mcap"))
    columns = read_timeseries_csv(recorded / "timeseries.csv")
    vehicles = 7  # Exp 2: the leader and 6 followers
    for k, (ns, message) in enumerate(messages["/tf"]):
        assert ns == round(columns["t"][k] * 1e9)
        transforms = message["transforms"]
        assert [tf["child_frame_id"] for tf in transforms] == [f"uav{i}" for i in range(vehicles)]
        for i, tf in enumerate(transforms):
            p = tf["translation"]
            assert (p["x"], p["y"], p["z"]) == (columns[f"uav{i}_px"][k], columns[f"uav{i}_py"][k],
                                                columns[f"uav{i}_pz"][k])
            assert tf["rotation"] == quaternion_zyx(columns[f"uav{i}_roll"][k],
                                                    columns[f"uav{i}_pitch"][k],
                                                    columns[f"uav{i}_yaw"][k])
    # The scene's boxes stand at the same poses; sigma_f and the sliding variables are the rows'
    k = len(messages["/tf"]) // 2
    cube = messages["/scene/vehicles"][k][1]["entities"][0]["cubes"][3]
    assert cube["pose"]["position"]["x"] == columns["uav3_px"][k]
    assert messages["/metrics/sigma_f"][k][1]["sigma_f"] == columns["sigma_f"][k]
    assert messages["/followers/sliding"][k][1]["sx"][0] == columns["uav1_sx"][k]
    slots = messages["/scene/formation"][k][1]["entities"][0]["spheres"]
    assert [s["pose"]["position"]["y"] for s in slots] == [columns[f"uav{i}_slot_y"][k]
                                                           for i in range(1, vehicles)]


def test_events_are_logs_at_their_times(recorded, tmp_path):
    messages, _, _, _ = read(write_mcap(recorded, tmp_path / "exp2.mcap"))
    events = json.loads((recorded / "summary.json").read_text())["events"]["list"]
    assert events, "the fixture's near-miss distance gives events"
    logs = messages["/events"]
    assert [m["message"] for _, m in logs[:-1]] == [e["what"] for e in events]
    assert [ns for ns, _ in logs[:-1]] == [round(e["time_s"] * 1e9) for e in events]
    assert all(m["level"] == 3 for _, m in logs[:-1])  # near misses: warnings
    assert logs[-1][1]["message"] == "run complete"
    assert [ns for ns, _ in logs] == sorted(ns for ns, _ in logs)


def test_quaternion_of_euler_angles():
    # A quarter turn of yaw, and of roll
    q = quaternion_zyx(0.0, 0.0, math.pi / 2)
    np.testing.assert_allclose([q["w"], q["x"], q["y"], q["z"]], [math.sqrt(0.5), 0, 0,
                                                                  math.sqrt(0.5)], atol=1e-15)
    q = quaternion_zyx(math.pi / 2, 0.0, 0.0)
    np.testing.assert_allclose([q["w"], q["x"], q["y"], q["z"]], [math.sqrt(0.5),
                                                                  math.sqrt(0.5), 0, 0], atol=1e-15)


def test_default_path_is_beside_the_run_and_nothing_is_replaced(recorded, capsys):
    # The run directory keeps only the runner's files (run --overwrite refuses any other)
    default = recorded.parent / "exp2.mcap"
    assert main([str(recorded)]) == 0
    assert capsys.readouterr().out.strip() == str(default)
    stamp = default.stat().st_mtime_ns
    with pytest.raises(SystemExit) as refused:
        main([str(recorded)])
    assert refused.value.code == 1 and "exists" in capsys.readouterr().err
    assert default.stat().st_mtime_ns == stamp
    assert main([str(recorded), "--overwrite"]) == 0
    assert not (recorded / "exp2.mcap").exists()
    default.unlink()


def test_module_runs_as_a_script(recorded, tmp_path):
    out = tmp_path / "script.mcap"
    result = subprocess.run([sys.executable, "-m", "mjfanalysis.mcap_export", str(recorded),
                             "-o", str(out)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert out.stat().st_size > 0

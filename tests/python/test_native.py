# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""An exported experiment flown through MuJoCo's own Python bindings (the `mujoco` package, the
native plugins loaded with mujoco.mj_loadPluginLibrary) flies the runner's trajectory."""

import os
from pathlib import Path

import mujoco
import numpy as np
import pytest

import mjformation


@pytest.fixture(scope="module")
def native_library() -> str:
    path = mjformation.native_plugin_library()
    mujoco.mj_loadPluginLibrary(path)
    return path


def sensor_block(model, data, name: str) -> np.ndarray:
    sensor = model.sensor(name)
    return data.sensordata[sensor.adr[0]:sensor.adr[0] + sensor.dim[0]].copy()


def test_exported_exp2_flies_the_runners_trajectory(exp2, tmp_path, native_library):
    scene = mjformation.export(exp2, tmp_path / "exp2")
    model = mujoco.MjModel.from_xml_path(str(scene))
    data = mujoco.MjData(model)
    sim = mjformation.Simulation(exp2)  # the runner, at its tick of t = 0
    n = sim.n_vehicles
    names = [(f"uav{i}_pos", f"uav{i}_vel") for i in range(n)]
    start = None
    for k in range(40000):
        if k % 500 == 0 or k == 39999:
            # mj_forward: the sensors of this step (the plugin's tick for it, held for mj_step)
            mujoco.mj_forward(model, data)
            native = np.array([np.concatenate([sensor_block(model, data, p),
                                               sensor_block(model, data, v)])
                               for p, v in names])
            runner = sim.states[:, 0:6]
            assert np.array_equal(native, runner), (k, np.abs(native - runner).max())
            start = native if start is None else start
        mujoco.mj_step(model, data)
        sim.step(1)
    assert data.time == pytest.approx(40.0)
    assert np.abs(native[:, 0:2] - start[:, 0:2]).max() > 10.0  # it flew


def test_export_refuses_what_the_native_path_cannot_carry(source, tmp_path):
    experiment = tmp_path / "late.toml"
    experiment.write_text((source / "experiments/exp2.toml").read_text()
                          + "\n[sensors]\nposition_latency = 1.5\n")
    with pytest.raises(ValueError, match=r"late.toml:\d+: \[sensors\] position_latency = 1.5 s"):
        mjformation.export(experiment, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_export_takes_set_as_run_does(exp2, tmp_path):
    scene = mjformation.export(exp2, tmp_path / "out", set={"formation.shape.radius": 7.25})
    assert "radius = 7.25" in scene.read_text()
    with pytest.raises(ValueError, match=r"stop_on: not carried"):
        mjformation.export(exp2, tmp_path / "stop", set={"run.stop_on": ["flip"]})


def test_a_scene_whose_rotor_was_deleted_is_refused_naming_it(exp2, tmp_path, native_library):
    import re
    scene = mjformation.export(exp2, tmp_path / "out").read_text()
    edited = re.sub(r'\s*<general name="uav1_rotor0"[^>]*/>', "", scene)
    assert edited != scene
    # Beside the files the scene names (relative to it): a scene read from a string has no folder.
    (tmp_path / "out/edited.xml").write_text(edited)
    # The compiler makes an mjData, so the plugin's init runs and refuses while compiling; the
    # mujoco package puts MuJoCo's warnings (the instance's message) into the error.
    with pytest.raises(ValueError, match="plugin->init failed(.|\n)*instance 'swarm': the scene "
                                         "has no actuator named 'uav1_rotor0'"):
        mujoco.MjModel.from_xml_path(str(tmp_path / "out/edited.xml"))


def test_export_never_replaces_a_users_directory(exp2, tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="exists and is not empty; pass --overwrite"):
        mjformation.export(exp2, out)
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt"]
    mjformation.export(exp2, out, overwrite=True)
    assert (out / "notes.txt").read_text() == "mine"
    assert (out / "scene.xml").is_file()


def run_example(source, name: str, *args) -> str:
    import subprocess
    import sys
    done = subprocess.run([sys.executable, str(source / "examples/mujoco_native" / name), *args],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def test_geometric_controller_flies_a_users_own_drone(source):
    # my_drone.xml: its own names, mjformation.attitude with geometric + hover; the script
    # exits 1 unless the drone holds the named point within 1 cm.
    assert "from the held point" in run_example(source, "fly_my_drone.py")


def test_sigma_f_from_mjdata_alone_is_the_runners(source, exp2, tmp_path):
    import sys
    sys.path.insert(0, str(source / "examples/mujoco_native"))
    import fly_exported
    scene = mjformation.export(exp2, tmp_path / "exp2")
    times, sigma = fly_exported.fly(str(scene), 5.0)
    run = mjformation.run(exp2, set={"run.duration": 5.0, "run.metric_window": [0.0, 5.0],
                                     "render.snapshots": []}, out=tmp_path / "run")
    recorded = np.loadtxt(tmp_path / "run/timeseries.csv", delimiter=",", skiprows=1,
                          usecols=(0, 1))
    for t, s in zip(times, sigma):
        row = recorded[np.argmin(np.abs(recorded[:, 0] - t))]
        assert abs(row[0] - t) < 1e-9
        assert s == pytest.approx(row[1], rel=1e-8), t  # the CSV keeps 9 significant digits
    assert sigma[0] == pytest.approx(53.8, abs=0.05)  # exp2.toml: sigma_f(0) = 53.8


def run_example_failing(source, name: str, *args) -> str:
    """The script's stderr when it refuses its input: one line, no traceback, exit status 1."""
    import subprocess
    import sys
    done = subprocess.run([sys.executable, str(source / "examples/mujoco_native" / name), *args],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "Traceback" not in done.stderr and done.stderr.count("\n") == 1, done.stderr
    return done.stderr


def test_fly_exported_refuses_bad_input_in_one_line(source, exp2, tmp_path):
    missing = tmp_path / "nowhere" / "scene.xml"
    assert f"{missing}: no such file; write one with `mjformation export" in run_example_failing(
        source, "fly_exported.py", str(missing))
    garbled = tmp_path / "garbled.xml"
    garbled.write_text("<mujoco><worldbody>\n</mujoco")
    assert f"{garbled}: line 2: not an XML file" in run_example_failing(
        source, "fly_exported.py", str(garbled))
    foreign = tmp_path / "foreign.xml"
    foreign.write_text("<mujoco><worldbody/></mujoco>")
    assert "no mjformation.swarm formation configuration; pass a scene" in run_example_failing(
        source, "fly_exported.py", str(foreign))
    scene = mjformation.export(exp2, tmp_path / "exp2")
    assert "--seconds -1: give a positive number" in run_example_failing(
        source, "fly_exported.py", str(scene), "--seconds", "-1")
    assert "--plot /proc/none/s.png: cannot write into /proc/none" in run_example_failing(
        source, "fly_exported.py", str(scene), "--plot", "/proc/none/s.png")


def test_export_takes_a_folder_and_a_bool(exp2, tmp_path, monkeypatch):
    """str(None) was the folder ./None and bool("no") is True: both refused before anything is
    written, as run refuses them."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(TypeError, match=r"out= takes a folder \(str or os.PathLike\), not None"):
        mjformation.export(exp2, None)
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(TypeError, match=r"overwrite= takes True or False, not 'no'"):
        mjformation.export(exp2, mine, overwrite="no")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine"]
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]


def experiment_files() -> list:
    """Every experiment file the project ships (laws.toml and the tuning spec are not runs)."""
    root = Path(os.environ.get("MJF_SOURCE_DIR", Path(__file__).resolve().parents[2]))
    return sorted(str(p.relative_to(root / "experiments"))
                  for p in (root / "experiments").rglob("*.toml")
                  if p.name != "laws.toml" and "tuning" not in p.parts)


# Files whose timed events (topology switches, a rotor fault, gusts) must lie inside the run:
# flown just past the last one, so that the event is flown through both faces too.
PAST_THE_LAST_EVENT = {"benchmark/b07_switching_topology.toml": 30.3,
                       "benchmark/b08_rotor_fault.toml": 15.3,
                       "benchmark/b10_gusts.toml": 39.0}


@pytest.mark.parametrize("name", experiment_files())
def test_every_experiment_file_exports_and_flies_the_runners_trajectory(name, source, tmp_path,
                                                                         native_library):
    """Export refuses nothing the runner flies: each file, exported and stepped with mj_step
    (for 0.3 s, or past its last timed event), ends with the runner's positions and velocities,
    bit for bit."""
    experiment = source / "experiments" / name
    duration = PAST_THE_LAST_EVENT.get(name, 0.3)
    short = {"run.duration": duration, "run.metric_window": [0.0, duration],
             "render.snapshots": []}
    scene = mjformation.export(experiment, tmp_path / "scene", set=short)
    model = mujoco.MjModel.from_xml_path(str(scene))
    data = mujoco.MjData(model)
    sim = mjformation.Simulation(experiment, set=short)
    steps = round(duration / model.opt.timestep)
    for _ in range(steps):
        mujoco.mj_step(model, data)
    sim.step(steps)
    mujoco.mj_forward(model, data)
    native = np.array([np.concatenate([sensor_block(model, data, f"uav{i}_pos"),
                                       sensor_block(model, data, f"uav{i}_vel")])
                       for i in range(sim.n_vehicles)])
    assert np.array_equal(native, sim.states[:, 0:6]), np.abs(native - sim.states[:, 0:6]).max()
    assert np.abs(native[:, 3:6]).max() > 0  # it moved

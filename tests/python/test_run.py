# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjformation.run / load / check / plugins / Simulation against the CLI of the same build."""

import json
import math
import subprocess
import warnings

import numpy as np
import pytest
from conftest import short

import mjformation


def summary_without_timing(path):
    s = json.loads(path.read_text())
    s.pop("timing")
    return s


def cli_run(cli, experiment, out, overrides=(), render=False):
    args = [cli, "run", str(experiment), "--out", str(out), "--quiet"]
    for o in overrides:
        args += ["--set", o]
    if not render:
        args.append("--no-render")
    return subprocess.run(args, capture_output=True, text=True)


def test_run_gives_the_bytes_of_the_cli_run(cli, exp2, tmp_path):
    # Given Exp 2 run by the CLI and by Python with the same override
    overrides = ["formation.q=3.0"]
    assert cli_run(cli, exp2, tmp_path / "cli", overrides).returncode == 0
    run = mjformation.run(exp2, set={"formation.q": 3.0}, out=tmp_path / "py")
    # Then every file is the same, byte for byte (summary.json but its timing)
    for name in ("timeseries.csv", "config.toml", "scene.xml", ".mjformation-run"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert summary_without_timing(tmp_path / "py/summary.json") == summary_without_timing(
        tmp_path / "cli/summary.json")
    assert run.complete and run.summary["metrics"]["sigma_f_mean"] > 0


def test_set_as_list_is_the_cli_syntax(exp2, tmp_path):
    run = mjformation.run(exp2, set=[f"{k}={v}" for k, v in {
        "run.duration": "2.0", "run.metric_window": "[0.0, 2.0]", "render.snapshots": "[]"}.items()],
        out=tmp_path / "r")
    assert run.summary["duration_s"] == 2.0 and run.complete


def test_bad_config_raises_value_error_with_the_cli_message(cli, exp2, tmp_path):
    # Given an override the runner refuses, and an unknown key
    for override, python_set in (("formation.q=-1.0", {"formation.q": -1.0}),
                                 ("run.durration=3.0", {"run.durration": 3.0})):
        cli_result = subprocess.run([cli, "check", str(exp2), "--set", override],
                                    capture_output=True, text=True)
        assert cli_result.returncode == 1
        message = cli_result.stderr.strip().removeprefix("mjformation: error: ")
        # Then run(), check() and Simulation() raise ValueError with the same message, which
        # names the override as its origin
        for call in (lambda: mjformation.run(exp2, set=python_set, out=tmp_path / "never"),
                     lambda: mjformation.check(exp2, set=python_set),
                     lambda: mjformation.Simulation(exp2, set=python_set)):
            with pytest.raises(ValueError) as error:
                call()
            assert str(error.value) == message
            assert str(error.value).startswith(f"--set {override.split('=')[0]}=")
        assert not (tmp_path / "never").exists()  # nothing written


def test_a_missing_experiment_file_is_a_file_not_found_error_saying_where(exp2, tmp_path):
    from mjformation.envs import FormationEnv

    missing = tmp_path / "nope.toml"
    for call in (lambda: mjformation.run(missing, out=tmp_path / "never"),
                 lambda: mjformation.check(missing),
                 lambda: mjformation.export(missing, tmp_path / "never"),
                 lambda: mjformation.sweep(missing, seeds=2, out=tmp_path / "never"),
                 lambda: mjformation.Simulation(missing),
                 lambda: FormationEnv(missing)):
        with pytest.raises(FileNotFoundError, match="does not exist.*the working folder is"):
            call()
    with pytest.raises(FileNotFoundError, match="is a folder"):
        mjformation.check(tmp_path)
    with pytest.raises(TypeError, match="a file's path"):
        mjformation.check(None)
    # A plugin folder that is not there, as the CLI's --plugin-path refuses it
    for call in (lambda: mjformation.run(exp2, out=tmp_path / "never", plugin_path=missing),
                 lambda: mjformation.check(exp2, plugin_path=[tmp_path, missing]),
                 lambda: mjformation.Simulation(exp2, plugin_path=missing)):
        with pytest.raises(FileNotFoundError, match="plugin_path: .*nope.toml is not a folder"):
            call()
    assert mjformation.check(exp2, plugin_path=tmp_path)  # an existing folder is searched
    assert not (tmp_path / "never").exists()  # nothing written


def test_what_export_does_not_carry_is_a_warning_python_can_filter(exp2, tmp_path):
    with pytest.warns(UserWarning, match=r"mjformation.export: \[render\] is not carried"):
        mjformation.export(exp2, tmp_path / "scene")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning escapes an explicit filter
        warnings.filterwarnings("ignore", message="mjformation.export")
        mjformation.export(exp2, tmp_path / "scene", overwrite=True)


def test_timeseries_is_the_analysis_loader_in_numpy(exp2, tmp_path):
    from mjfanalysis import io

    run = mjformation.run(exp2, set=short(3.0), out=tmp_path / "r")
    columns = run.timeseries
    # mjfanalysis reads through the module's loader when it is importable ...
    assert io.module_reader() is mjformation._core.read_csv
    for name, values in io.read_timeseries(tmp_path / "r/timeseries.csv").items():
        np.testing.assert_array_equal(columns[name], values, err_msg=name)
    # ... and its pure-Python reader gives the same arrays
    reference = io.read_timeseries_csv(tmp_path / "r/timeseries.csv")
    assert list(columns) == list(reference)
    for name, values in reference.items():
        np.testing.assert_array_equal(columns[name], values, err_msg=name)  # NaN == NaN here
    assert len(columns["t"]) == 301 and math.isnan(columns["uav0_sx"][0])


def test_frame_is_the_tidy_long_form(exp2, tmp_path):
    pytest.importorskip("pandas")
    run = mjformation.run(exp2, set=short(1.0), out=tmp_path / "r")
    frame = run.frame()
    ts = run.timeseries
    assert len(frame) == 7 * len(ts["t"])
    follower3 = frame[frame.vehicle == 3]
    np.testing.assert_array_equal(follower3["px"].to_numpy(), ts["uav3_px"])
    np.testing.assert_array_equal(follower3["slot_y"].to_numpy(), ts["uav3_slot_y"])


def test_load_reads_a_cli_run(cli, exp2, tmp_path):
    assert cli_run(cli, exp2, tmp_path / "cli", [f"{k}={json.dumps(v)}" for k, v in short(1.0).items()]).returncode == 0
    run = mjformation.load(tmp_path / "cli")
    assert run.config["run"]["name"] == "exp2" and run.summary["complete"] is True
    assert run.timeseries["t"][-1] == 1.0
    with pytest.raises(FileNotFoundError):
        mjformation.load(tmp_path)


def test_out_none_is_a_temporary_directory_removed_with_the_run(exp2):
    run = mjformation.run(exp2, set=short(0.5))
    path = run.path
    assert (path / "summary.json").is_file()
    del run
    assert not path.exists()


def test_plugins_and_check(exp2):
    names = {p["name"]: p for p in mjformation.plugins()}
    assert {"smc_discrete", "consensus_linear", "circle", "pd_cascade", "python"} <= set(names)
    assert names["smc_discrete"]["attributes"]["q"]["default"] is not None
    assert names["python_agent"]["kind"] == "per-agent formation"
    info = mjformation.check(exp2)
    assert info["formation"] == "smc_discrete" and info["followers"] == 6


def test_simulation_steps_to_the_recorded_rows(exp2, tmp_path):
    # Given the run and a Simulation of the same experiment
    run = mjformation.run(exp2, set=short(1.0), out=tmp_path / "r")
    sim = mjformation.Simulation(exp2, set=short(1.0))
    ts = run.timeseries
    assert sim.time == 0.0 and sim.states.shape == (7, 13)
    for row, t in ((0, 0.0), (50, 0.5), (100, 1.0)):
        sim.step(round(t / 0.001) - sim.step_index)
        assert sim.time == pytest.approx(t)
        # Then states and slots are those of the timeseries row at that time (9 digits)
        for v in range(7):
            for k, col in enumerate(("px", "py", "pz", "vx", "vy", "vz")):
                assert sim.states[v, k] == pytest.approx(ts[f"uav{v}_{col}"][row], rel=1e-8, abs=1e-9)
            assert sim.slots[v, 0] == pytest.approx(ts[f"uav{v}_slot_x"][row], rel=1e-8, abs=1e-9)
            assert sim.setpoints[v, 0] == pytest.approx(ts[f"uav{v}_ax_cmd"][row], rel=1e-8, abs=1e-9)
    assert sim.step(10**6).step_index == sim.total_steps  # stops at the end
    g = sim.graph
    assert g.leader_weight.tolist() == [1, 0, 0, 0, 0, 0] and g.adjacency[0, 1] == 1.0
    assert np.allclose(g.laplacian.sum(axis=1), g.leader_weight)


def test_simulation_scales_the_metric_window_of_a_shorter_run(exp2, recwarn):
    # exp2.toml averages over [25, 40] s of 40 s, a window the runner refuses in a 0.4 s run:
    # a duration alone scales it, as run() does, and says so at the caller's line
    with pytest.warns(UserWarning, match=r"mjformation\.Simulation: .*proportionate window "
                                         r"\[0\.25, 0\.4\] s; pass run\.metric_window") as caught:
        sim = mjformation.Simulation(exp2, set={"run.duration": 0.4})
    assert [w.filename for w in caught if "proportionate" in str(w.message)] == [__file__]
    assert sim.step(10**6).step_index == sim.total_steps == 400
    driven = mjformation.Simulation(exp2, set=["run.duration=0.4"], driven=True)  # the CLI's syntax
    assert driven.total_steps == 400
    # A window given is kept, without a warning
    recwarn.clear()
    mjformation.Simulation(exp2, set={"run.duration": 0.4, "run.metric_window": [0.0, 0.4]})
    assert not [w for w in recwarn if "proportionate" in str(w.message)]

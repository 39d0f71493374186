# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Scenes that travel (docs/PLUGINS.md): an exported folder holds every file its scene names,
by paths relative to the scene, and flies the same bits after it is moved; the native plugin
library finds our plugin libraries beside itself; `import mjformation` registers the native
plugins, so a plain mujoco.MjModel.from_xml_path flies an export (no mj_loadPluginLibrary in
this file)."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest

import mjformation

STEPS = 300
SHORT = {"run.duration": 1.0, "run.metric_window": [0.0, 1.0]}


def fly(scene: Path) -> np.ndarray:
    """qpos and act of every step of a plain mj_step flight of `scene`."""
    model = mujoco.MjModel.from_xml_path(str(scene))
    data = mujoco.MjData(model)
    out = []
    for _ in range(STEPS):
        mujoco.mj_step(model, data)
        out.append(np.concatenate([data.qpos, data.act]))
    return np.array(out)


def named_paths(scene: Path) -> list[str]:
    """Every file the scene names: asset `file` attributes and the paths in the <config> values
    (model, scene, file, plugin_path)."""
    text = scene.read_text()
    files = re.findall(r'\bfile="([^"]*)"', text)
    files += re.findall(r"\b(?:model|scene|file) = &quot;([^&]*)&quot;", text)
    return files


@pytest.fixture(scope="module")
def trajectory(source) -> Path:
    """Exp 2 with a recorded leader path: a data file beside the experiment."""
    return source / "experiments/leaders/exp2_trajectory.toml"


def test_export_bundles_what_the_scene_names_by_relative_paths(trajectory, tmp_path):
    scene = mjformation.export(trajectory, tmp_path / "out", set=SHORT)
    out = scene.parent
    names = named_paths(scene)
    assert "data/recorded_path.csv" in names, names
    assert any(n.startswith("vehicle/") and n.endswith(".xml") for n in names), names
    for name in names:
        assert not name.startswith("/"), name
        assert (out / name).is_file(), name
    assert (out / "data/recorded_path.csv").read_bytes() == \
        (trajectory.parent / "data/recorded_path.csv").read_bytes()
    # Nothing of the source tree is named any more (the opening comment says where it came from).
    body = re.sub(r"<!--.*?-->", "", scene.read_text(), flags=re.S)
    assert str(trajectory.parents[2]) not in body


def test_a_moved_folder_flies_the_same_bits(trajectory, tmp_path, monkeypatch):
    # The experiment and its data file in a folder of their own, gone before the moved scene flies.
    source = tmp_path / "source"
    (source / "data").mkdir(parents=True)
    shutil.copy(trajectory, source)
    shutil.copy(trajectory.parent / "data/recorded_path.csv", source / "data")
    scene = mjformation.export(source / trajectory.name, tmp_path / "here", set=SHORT)
    before = fly(scene)
    shutil.rmtree(source)
    moved = tmp_path / "elsewhere/deeper/moved"
    moved.parent.mkdir(parents=True)
    shutil.move(str(scene.parent), str(moved))
    assert not scene.exists()
    after = fly(moved / "scene.xml")
    assert np.array_equal(before, after)
    assert np.abs(after[-1] - after[0]).max() > 1e-3  # it flew
    # Loaded by a relative name from another working folder: the same files, the same bits.
    monkeypatch.chdir(moved.parent)
    assert np.array_equal(fly(Path("moved/scene.xml")), before)


def test_a_copied_library_flies_with_the_plugins_beside_it(trajectory, tmp_path):
    """The native library and our plugin libraries copied into one folder, loaded by stock MuJoCo
    in a process that never imports mjformation: the plugins come from that folder ($ORIGIN,
    dladdr), and the flight is the build tree's, bit for bit."""
    scene = mjformation.export(trajectory, tmp_path / "scene", set=SHORT)
    reference = fly(scene)
    lib = tmp_path / "lib"
    lib.mkdir()
    shutil.copy(mjformation.native_plugin_library(), lib)
    for library in {p["library"] for p in mjformation.plugins()}:
        if library.endswith(".so"):  # not the in-process laws of the Python module
            shutil.copy(library, lib)
    np.save(tmp_path / "reference.npy", reference)
    script = f"""
import sys
import mujoco
import numpy as np
assert "mjformation" not in sys.modules
mujoco.mj_loadPluginLibrary({str(lib / "libmjformation_mujoco.so")!r})
model = mujoco.MjModel.from_xml_path({str(scene)!r})
data = mujoco.MjData(model)
out = []
for _ in range({STEPS}):
    mujoco.mj_step(model, data)
    out.append(np.concatenate([data.qpos, data.act]))
assert np.array_equal(np.array(out), np.load({str(tmp_path / "reference.npy")!r}))
maps = open("/proc/self/maps").read()
for name in ("libmjformation_mujoco.so", "libmjf_formation.so", "libmjf_guidance.so",
             "libmjf_attitude.so"):
    mapped = {{line.split()[-1] for line in maps.splitlines() if line.endswith("/" + name)}}
    assert mapped == {{{str(lib)!r} + "/" + name}}, (name, mapped)
print("ok")
"""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MJF_PLUGIN_PATH")}
    result = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0 and result.stdout.strip() == "ok", result.stderr


def test_our_libraries_find_their_neighbours_by_origin():
    """The native library and every plugin family: RUNPATH $ORIGIN (readelf -d)."""
    readelf = shutil.which("readelf")
    if readelf is None:
        pytest.skip("readelf (binutils) is not installed")
    libraries = {mjformation.native_plugin_library()}
    libraries |= {p["library"] for p in mjformation.plugins() if p["library"].endswith(".so")}
    assert len(libraries) >= 5, libraries
    for library in libraries:
        dynamic = subprocess.run([readelf, "-d", library], capture_output=True, text=True,
                                 check=True).stdout
        runpath = [line for line in dynamic.splitlines() if "RUNPATH" in line or "RPATH" in line]
        assert any("$ORIGIN" in line for line in runpath), (library, runpath)


def test_overwrite_replaces_only_what_export_wrote(trajectory, tmp_path):
    out = tmp_path / "out"
    mjformation.export(trajectory, out, set=SHORT)
    mjformation.export(trajectory, out, overwrite=True, set=SHORT)  # its own files: replaced
    (out / "data/recorded_path.csv").unlink()
    (out / "data/recorded_path.csv").write_text("t,x\nmine\n")
    (out / "mjformation_export.txt").write_text("")  # export no longer knows it wrote the file
    with pytest.raises(ValueError, match="recorded_path.csv: exists and was not written by export"):
        mjformation.export(trajectory, out, overwrite=True, set=SHORT)
    assert (out / "data/recorded_path.csv").read_text() == "t,x\nmine\n"


def test_a_vehicle_mesh_travels_with_the_scene(source, tmp_path):
    """A vehicle model whose mesh lies below it (meshdir): the mesh is copied below the model's
    copy, the composed scene names that copy, and the folder flies after the originals are gone."""
    vehicle = tmp_path / "vehicle"
    (vehicle / "meshes").mkdir(parents=True)
    shutil.copy(source / "examples/vehicles/bumblebee/assets/canopy.obj", vehicle / "meshes")
    text = (source / "mjcf/quadrotor.xml").read_text()
    text = text.replace('inertiafromgeom="false"/>', 'inertiafromgeom="false" meshdir="meshes"/>')
    text = text.replace("<asset>", '<asset>\n    <mesh name="canopy" file="canopy.obj"/>', 1)
    text = text.replace('<site name="imu"', '<geom class="quad_visual" type="mesh" mesh="canopy"/>'
                        '\n      <site name="imu"', 1)
    (vehicle / "meshed.xml").write_text(text)
    experiment = tmp_path / "meshed.toml"
    experiment.write_text(
        '[run]\nduration = 1.0\nmetric_window = [0.0, 1.0]\n'
        '[vehicles]\nmodel = "vehicle/meshed.xml"\nfollowers = 2\n'
        '[formation]\nplugin = "smc_discrete"\n'
        '[formation.shape]\ntype = "circle"\nradius = 3.0\nomega = 0.0\n')
    scene = mjformation.export(experiment, tmp_path / "out")
    assert 'file="vehicle/meshes/canopy.obj"' in scene.read_text()
    assert (scene.parent / "vehicle/meshes/canopy.obj").is_file()
    before = fly(scene)
    shutil.rmtree(vehicle)
    shutil.move(str(scene.parent), str(tmp_path / "moved"))
    assert np.array_equal(fly(tmp_path / "moved/scene.xml"), before)


def test_files_export_cannot_carry_are_refused_by_name(source, tmp_path):
    """A model's <include>d file and an asset file outside the model's folder would be missing
    from the exported folder: refused, naming the model and the file."""
    quadrotor = (source / "mjcf/quadrotor.xml").read_text()
    (tmp_path / "models/parts").mkdir(parents=True)
    (tmp_path / "models/parts/empty.xml").write_text("<mujoco/>\n")
    (tmp_path / "models/included.xml").write_text(
        quadrotor.replace("<worldbody>", '<include file="parts/empty.xml"/>\n  <worldbody>', 1))
    shutil.copy(source / "examples/vehicles/bumblebee/assets/canopy.obj", tmp_path)
    above = Path(os.pardir) / "canopy.obj"  # the model's folder's parent: the temporary folder
    (tmp_path / "models/outside.xml").write_text(
        quadrotor.replace("<asset>", f'<asset>\n    <mesh name="canopy" file="{above}"/>', 1))
    for model, message in (("included.xml", r"included\.xml: includes other MJCF files"),
                           ("outside.xml", r"outside\.xml: asset file .*canopy\.obj lies outside")):
        experiment = tmp_path / f"{model}.toml"
        experiment.write_text(f'[vehicles]\nmodel = "models/{model}"\nfollowers = 1\n'
                              '[formation]\nplugin = "smc_discrete"\n'
                              '[formation.shape]\ntype = "circle"\nradius = 3.0\n')
        with pytest.raises(ValueError, match=message):
            mjformation.export(experiment, tmp_path / f"out_{model}")
        assert not (tmp_path / f"out_{model}").exists()

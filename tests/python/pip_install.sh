#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# `pip install .` as a user of a machine prepared by scripts/setup.sh would run it, offline: a
# fresh virtual environment holding the project environment's packages (requirements.txt, copied
# from it, so nothing is downloaded), then `pip wheel --no-build-isolation --no-deps --no-index
# SOURCE` and the wheel installed (pip install . builds the same wheel and installs it). Exp 2 then flies, briefly, through the `mjformation` command, through `import
# mjformation`, and through stock MuJoCo (`import mujoco` loads our native plugins by its entry
# point), from the installed package's own files: every folder the runner searches for plugins
# and models lies in the package.
# Usage: pip_install.sh SOURCE_DIR PROJECT_ENV WORK_DIR
set -euo pipefail
source_dir=$(cd "$1" && pwd)
project_env=$2
work=$3
rm -rf "$work/venv" "$work/runs"
mkdir -p "$work"
start=$(date +%s)

/usr/bin/python3 -m venv "$work/venv"
site=$("$work/venv/bin/python" -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
project_site=$("$project_env/bin/python" -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
cp -a "$project_site/." "$site/"
rm -rf "$site"/mjformation* "$site"/mjfanalysis*  # a copy of an earlier install, if any

# The build directory persists under WORK_DIR: a second run is an incremental build.
launcher=""
if command -v ccache >/dev/null; then
  launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache"
fi
# `pip wheel`, then the wheel alone installed: what another machine with the same runtime
# packages would be handed (docs/PYTHON.md, "Installing with pip").
rm -rf "$work/wheel"
CMAKE_ARGS="$launcher" "$work/venv/bin/python" -m pip wheel -q --no-build-isolation --no-deps \
  --no-index --config-settings=build-dir="$work/build" --wheel-dir "$work/wheel" "$source_dir"
wheels=("$work"/wheel/mjformation-*.whl)
"$work/venv/bin/python" -m pip install -q --no-deps --no-index "${wheels[0]}"
built=$(date +%s)
echo "pip wheel and install: $((built - start)) s"

package="$site/mjformation"
experiment="$package/share/mjformation/experiments/exp2.toml"
short=(--set run.duration=1.0 --set 'run.metric_window=[0.0, 1.0]' --set 'render.snapshots=[]')
cd "$work"  # not the source tree

# The command on PATH is the package's runner, which finds its plugins and models in the package.
version=$("$work/venv/bin/mjformation" --version)
echo "$version"
grep -q "installed in $package" <<<"$version"
for dir in $(sed -n 's/^\(plugin\|model\) search path://p' <<<"$version"); do
  if [[ "$dir" != "$package"/* ]]; then
    echo "the installed runner searches $dir, outside its package $package" >&2
    exit 1
  fi
done
"$work/venv/bin/mjformation" run "$experiment" --out "$work/runs/cli" --quiet --no-render "${short[@]}"

# Stock MuJoCo: `import mujoco` alone (no mjformation) loads our native plugins through the
# mujoco.plugins entry point and flies the scene the command exported, from the folder moved
# (it names its files relative to itself, and no folder of the package: docs/PLUGINS.md).
"$work/venv/bin/mjformation" export "$experiment" --out "$work/runs/native" >/dev/null
mv "$work/runs/native" "$work/runs/native_moved"
"$work/venv/bin/python" - "$work/runs/native_moved/scene.xml" "$package" <<'PY'
import re
import sys

import mujoco

assert "mjformation" not in sys.modules
text = re.sub(r"<!--.*?-->", "", open(sys.argv[1]).read(), flags=re.S)
assert sys.argv[2] not in text, "the exported scene names a folder of the package"
model = mujoco.MjModel.from_xml_path(sys.argv[1])  # refused if the plugins were not registered
data = mujoco.MjData(model)
start = data.sensor("uav1_pos").data.copy()
while data.time < 1.0:
    mujoco.mj_step(model, data)
moved = abs(data.sensor("uav1_pos").data - start).max()
assert moved > 0.01, moved
print(f"stock MuJoCo flight OK (follower 1 moved {moved:.2f} m)")
PY

# The module: the same run as the command's, byte for byte, from the installed package.
"$work/venv/bin/python" - "$experiment" "$work" "$package" <<'PY'
import sys
from pathlib import Path

experiment, work, package = sys.argv[1], Path(sys.argv[2]), sys.argv[3]
import mjformation

assert mjformation.__file__.startswith(package), mjformation.__file__
assert mjformation.native_plugin_library().startswith(package), mjformation.native_plugin_library()
run = mjformation.run(experiment, out=work / "runs/module", set={
    "run.duration": 1.0, "run.metric_window": [0.0, 1.0], "render.snapshots": []})
assert run.complete
cli = (work / "runs/cli/timeseries.csv").read_bytes()
assert (work / "runs/module/timeseries.csv").read_bytes() == cli, "module and command differ"
print("module run OK: the command's bytes")
PY
echo "pip install and three flights: $(($(date +%s) - start)) s"

#!/usr/bin/env bash
# find_package(mjformation): installs the build into a prefix, builds examples/plugin against it
# with CMake alone, moves the prefix (it must work wherever it is), then the moved runner finds
# its own models and the example plugin (by --plugin-path, and once installed into the prefix
# without it) and flies a short experiment with it. Usage: BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
trap 'echo "cmake_package.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
build=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
test -f "$work/prefix/lib/cmake/mjformation/mjformationConfig.cmake"
cmake -S "$src/examples/plugin" -B "$work/example-build" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release > "$work/configure.txt"
grep -q "mjformation plugin ABI [0-9]" "$work/configure.txt" || { cat "$work/configure.txt"; false; }
cmake --build "$work/example-build" > "$work/build.txt" 2>&1 || { cat "$work/build.txt"; false; }
test -f "$work/example-build/libexample_orbit.so"
# Only the entry point is exported.
exported=$(nm -D --defined-only "$work/example-build/libexample_orbit.so" | awk '$2 == "T" {print $3}')
[ "$exported" = "mjf_plugin_entry" ] || { echo "exported: $exported"; false; }

# Move the prefix: nothing in it may point at where it was installed or at this build.
mv "$work/prefix" "$work/moved"
bin="$work/moved/bin/mjformation"
"$bin" --version | grep -Eq "^mjformation [0-9.]+ \(MuJoCo [0-9.]+, plugin ABI [0-9]+\)"
# Standalone: the moved tree runs with the MuJoCo library it carries, not the build's.
"$bin" --version | grep -q "^MuJoCo library: $work/moved/lib/libmujoco.so" ||
  { "$bin" --version; false; }
cat > "$work/exp.toml" <<'T'
[run]
name = "orbit"
duration = 4.0
[vehicles]
followers = 1
altitude = 2.0
leader_start = [0.0, 0.0]
follower_start = [[-3.0, -3.0]]
[topology]
leader_links = [1]
[leader]
plugin = "example_orbit"
radius = 2.0
omega = 0.5
[formation]
plugin = "hover"
[attitude]
plugin = "pd_cascade"
T
"$bin" check "$work/exp.toml" --plugin-path "$work/example-build" > "$work/check.txt"
# The model comes from the moved prefix, not from the source tree.
grep -q "model $work/moved/share/mjformation/mjcf/quadrotor.xml" "$work/check.txt" ||
  { cat "$work/check.txt"; false; }
"$bin" run "$work/exp.toml" --out "$work/run" --plugin-path "$work/example-build" --no-render -q
grep -q '"complete": true' "$work/run/summary.json"
grep -q '"name": "example_orbit"' "$work/run/summary.json"
# The leader flew the orbit: 4 s at 0.5 rad/s from (0, 0) about (-2, 0): it ends near
# (-2 + 2 cos 2, 2 sin 2) = (-2.83, 1.82). Column 3, 4 = uav0_px, uav0_py.
python3 - "$work/run/timeseries.csv" <<'PY'
import csv, math, sys
rows = list(csv.reader(open(sys.argv[1])))
h, last = rows[0], rows[-1]
x, y = float(last[h.index("uav0_px")]), float(last[h.index("uav0_py")])
ex, ey = -2 + 2 * math.cos(2.0), 2 * math.sin(2.0)
err = math.hypot(x - ex, y - ey)
assert err < 0.3, f"leader at ({x:.2f}, {y:.2f}), orbit reference ({ex:.2f}, {ey:.2f})"
print(f"example_orbit: leader {err:.3f} m from its reference after 4 s")
PY
# The example formation law declares the contract's period and q (docs/PLUGINS.md): the runner
# reads them back into summary.json's plugin report.
test -f "$work/example-build/libexample_sampled_law.so"
# The plain-C formation law: the project declares LANGUAGES C CXX (docs/PLUGINS.md).
test -f "$work/example-build/libexample_consensus_c.so"
"$bin" run "$work/exp.toml" --out "$work/run_law" --plugin-path "$work/example-build" --no-render \
  -q --set formation.plugin='"example_sampled_law"' \
  --set 'formation.shape={type="circle",radius=3.0,omega=0.3}'
grep -q '"complete": true' "$work/run_law/summary.json"
python3 - "$work/run_law/summary.json" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))["plugin_report"]
assert report == {"period": 0.02, "q": 5.0}, report
PY
# Installed into the same (moved) prefix, the runner finds it with no --plugin-path.
cmake --install "$work/example-build" --prefix "$work/moved" >/dev/null
"$bin" plugins > "$work/plugins.txt"
grep -q "example_orbit" "$work/plugins.txt" || { cat "$work/plugins.txt"; false; }
grep -q "library: $work/moved/lib/mjformation/plugins/libexample_orbit.so" \
  "$work/plugins.txt" || { cat "$work/plugins.txt"; false; }
grep -q "library: $work/moved/lib/mjformation/plugins/libmjf_attitude.so" \
  "$work/plugins.txt" || { cat "$work/plugins.txt"; false; }
# The moved install stands alone: it searches only its own prefix and runs Exp 2 from its share/.
"$bin" --version > "$work/version.txt"
grep -q "installed in $work/moved" "$work/version.txt" || { cat "$work/version.txt"; false; }
# (The work folder lies inside the build tree: look for the build tree's own folders.)
tree_paths=(-e "$build/plugins" -e "$build/lib" -e "$src/mjcf")
if grep -F -q "${tree_paths[@]}" "$work/version.txt"; then cat "$work/version.txt"; false; fi
share="$work/moved/share/mjformation"
for f in experiments/exp2.toml mjcf/README.md docs/VEHICLES.md analysis/report.py examples/plugin/CMakeLists.txt; do
  test -f "$share/$f" || { echo "not installed: share/mjformation/$f"; false; }
done
(cd "$work" && "$bin" run "$share/experiments/exp2.toml" --out "$work/exp2" --no-render -q \
  --set run.duration=2 --set 'run.metric_window=[1.0, 2.0]' --set 'render.snapshots=[1.0]' \
  --set 'attitude.plugin="geometric"')
grep -q '"complete": true' "$work/exp2/summary.json"
if grep -F -q "${tree_paths[@]}" "$work/exp2/summary.json" "$work/exp2/scene.xml"; then
  echo "the installed run used the build or source tree"; false
fi
grep -q '"attitude_report"' "$work/exp2/summary.json"
echo "cmake package: example plugin configured, built, loaded from a moved prefix: OK"

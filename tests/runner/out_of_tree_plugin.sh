#!/usr/bin/env bash
# A plugin written in plain C, compiled outside the source tree against the INSTALLED header
# only, loads from a config line and flies the leader. Usage: BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
trap 'echo "out_of_tree_plugin.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
build=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/plugins"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cat > "$work/oot_hold.c" <<'C'
#include <mjformation/plugin.h>
#include <stdlib.h>
typedef struct { int vehicle; double x, y; } Hold;
static const mjfAttribute kAttributes[] = {{"gain", "1.5", "1/s^2: position gain"}};
static void* Create(const mjfCreateContext* ctx) {
  Hold* h = malloc(sizeof(Hold));
  h->vehicle = ctx->vehicle; h->x = ctx->initial_pos[0]; h->y = ctx->initial_pos[1];
  return h;
}
static int Compute(void* instance, const mjfStepContext* ctx) {
  Hold* h = instance;
  mjfSetpoint* sp = &ctx->setpoints[h->vehicle];
  const mjfVehicleState* s = &ctx->states[h->vehicle];
  sp->pos[0] = h->x; sp->pos[1] = h->y;
  sp->acc[0] = 1.5 * (h->x - s->pos[0]) - 2.0 * s->vel[0];
  sp->acc[1] = 1.5 * (h->y - s->pos[1]) - 2.0 * s->vel[1];
  return 0;
}
static void Destroy(void* instance) { free(instance); }
static const mjfPlugin kHold = {MJF_ABI_VERSION, "oot_hold", MJF_KIND_GUIDANCE,
  "out-of-tree test plugin", 1, kAttributes, 0, NULL, Create, Compute, NULL, Destroy, NULL,
  NULL, NULL, NULL};  /* ABI 4: no state */
/* ABI 3: an estimator plugin (the held samples, as passthrough does). */
static void* EstCreate(const mjfCreateContext* ctx) { (void)ctx; return malloc(1); }
static int EstCompute(void* instance, const mjfStepContext* ctx) {
  (void)instance;
  ctx->estimate->state = *ctx->estimator->held;
  return 0;
}
static const mjfPlugin kEst = {MJF_ABI_VERSION, "oot_estimator", MJF_KIND_ESTIMATOR,
  "out-of-tree estimator", 0, NULL, 0, NULL, EstCreate, EstCompute, NULL, Destroy, NULL,
  NULL, NULL, NULL};
static const mjfPlugin* const kPlugins[] = {&kHold, &kEst};
const mjfPlugin* const* mjf_plugin_entry(int* count) { *count = 2; return kPlugins; }
C
cc -std=c11 -Wall -Wextra -Werror -shared -fPIC -I"$work/prefix/include" \
   -o "$work/plugins/liboot_hold.so" "$work/oot_hold.c"
cat > "$work/exp.toml" <<'T'
[run]
name = "oot"
duration = 1.0
[vehicles]
followers = 1
altitude = 2.0
leader_start = [0.0, 0.0]
follower_start = [[3.0, 0.0]]
[topology]
leader_links = [1]
[leader]
plugin = "oot_hold"
gain = 2.0
[formation]
plugin = "hover"
[attitude]
plugin = "pd_cascade"
T
"$work/prefix/bin/mjformation" plugins --plugin-path "$work/plugins" > "$work/plugins.txt"
grep -q "oot_hold" "$work/plugins.txt" || { cat "$work/plugins.txt"; false; }
# The installed header is ABI 4 and lists the estimator kind, with the C estimator under it.
grep -q "#define MJF_ABI_VERSION 4u" "$work/prefix/include/mjformation/plugin.h"
sed -n '/^estimator plugins:/,$p' "$work/plugins.txt" | grep -q "oot_estimator" \
  || { cat "$work/plugins.txt"; false; }
"$work/prefix/bin/mjformation" run "$work/exp.toml" --out "$work/run" \
    --plugin-path "$work/plugins" --no-render -q
grep -q '"complete": true' "$work/run/summary.json"
grep -q '"name": "oot_hold"' "$work/run/summary.json"
# The same plugin through the native MuJoCo plugins' bridge: the experiment exported (its
# [run] plugin_path names the plugin's folder), loaded by MuJoCo's own Python bindings with the
# installed libmjformation_mujoco.so, flies the leader where the runner flew it.
# Not in the sanitizer build: its plugin library needs the ASan runtime first in the process,
# which an uninstrumented Python cannot give (as its Python module, it is not built there).
python_env=$(sed -n 's/^MJF_PYTHON_ENV:[A-Z]*=//p' "$build/CMakeCache.txt")
sanitized=$(sed -n 's/^MJF_SANITIZE:BOOL=//p' "$build/CMakeCache.txt")
if [ "$sanitized" = ON ]; then
  echo "native: skipped in the sanitizer build (tests/mujoco_plugin flies the bridge there)"
elif [ -x "$python_env/bin/python" ]; then
  sed "s|^duration = 1.0|duration = 1.0\nplugin_path = [\"$work/plugins\"]|" "$work/exp.toml" \
    > "$work/exp_native.toml"
  "$work/prefix/bin/mjformation" export "$work/exp_native.toml" -o "$work/native" 2>/dev/null
  "$python_env/bin/python" - "$work/prefix/lib/libmjformation_mujoco.so" \
      "$work/native/scene.xml" "$work/run/timeseries.csv" <<'PY'
import csv, sys
import mujoco
mujoco.mj_loadPluginLibrary(sys.argv[1])
m = mujoco.MjModel.from_xml_path(sys.argv[2])
d = mujoco.MjData(m)
while d.time < 1.0 - 1e-9:
    mujoco.mj_step(m, d)
mujoco.mj_forward(m, d)
rows = list(csv.DictReader(open(sys.argv[3])))
last = rows[-1]
adr = m.sensor("uav0_pos").adr[0]
x, y = d.sensordata[adr], d.sensordata[adr + 1]
assert abs(float(last["t"]) - d.time) < 1e-9, (last["t"], d.time)
# The CSV keeps 9 significant digits; the C++ test compares the bits (mujoco_plugin_test).
for axis, value in (("px", x), ("py", y)):
    assert abs(float(last["uav0_" + axis]) - value) < 1e-6, (axis, last["uav0_" + axis], value)
print(f"native: the out-of-tree plugin flew the leader to ({x:.9g}, {y:.9g}), as the runner did")
PY
fi
# The same plain-C plugin through the CMake route (find_package + mjformation_add_plugin): the
# helper hides C++ symbols, yet the entry point of a C source, written with or without
# MJF_PLUGIN_EXPORT, is exported, and it is the only exported symbol.
for variant in plain macro; do
  mkdir -p "$work/cmake_$variant"
  if [ $variant = macro ]; then
    sed 's/^const mjfPlugin\* const\* mjf_plugin_entry/MJF_PLUGIN_EXPORT &/' "$work/oot_hold.c" \
      > "$work/cmake_$variant/oot_hold.c"
    grep -q "^MJF_PLUGIN_EXPORT const mjfPlugin" "$work/cmake_$variant/oot_hold.c"
  else
    cp "$work/oot_hold.c" "$work/cmake_$variant/oot_hold.c"
  fi
  cat > "$work/cmake_$variant/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.22)
project(oot_c C CXX)
find_package(mjformation REQUIRED)
add_compile_options(-Wall -Wextra -Werror)
mjformation_add_plugin(oot_hold_cmake SOURCES oot_hold.c NO_INSTALL)
CM
  cmake -S "$work/cmake_$variant" -B "$work/cmake_$variant/build" \
    -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
  cmake --build "$work/cmake_$variant/build" >/dev/null
  lib="$work/cmake_$variant/build/liboot_hold_cmake.so"
  exported=$(nm -D --defined-only "$lib" | awk '$2 == "T" || $2 == "D" || $2 == "R" {print $3}')
  [ "$exported" = "mjf_plugin_entry" ] || { echo "$variant: exported: $exported"; false; }
  "$work/prefix/bin/mjformation" plugins --plugin-path "$work/cmake_$variant/build" \
    > "$work/cmake_$variant/plugins.txt"
  grep -q "oot_hold" "$work/cmake_$variant/plugins.txt" \
    || { cat "$work/cmake_$variant/plugins.txt"; false; }
done
echo "out-of-tree plugin: built against $work/prefix/include, loaded and run: OK"

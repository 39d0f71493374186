#!/usr/bin/env bash
# Issue 12's robustness map: Exps 1 (exponential), 2, 3 x tilt_max {0.35 .. 0.78} x attitude
# plugin, each plugin at its default gains, on the quadrotor; then the table
# (MAP_DIR/map.md, map.csv; docs/RESULTS.md quotes it).
# pd_cascade refuses tilt_max > 0.65 rad with its default (paper) damping and allocation, so it
# is run twice: as the paper's cascade, and with both large-tilt fixes switched on.
# Usage: scripts/robustness_map.sh [MAP_DIR]   (default results/robustness; about 1 minute)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# The analysis entry scripts import mjfanalysis: installed, or from the source tree (analysis/README.md).
export PYTHONPATH="$root/analysis${PYTHONPATH:+:$PYTHONPATH}"
out=${1:-$root/results/robustness}
bin=$root/build/runner/mjformation
[ -x "$bin" ] || MJF_BUILD_TARGET=mjformation bash "$root/scripts/build.sh" "$root/build"
tilts=0.35,0.45,0.55,0.65,0.78
declare -A plugins=(
  [pd_cascade]='attitude={plugin="pd_cascade"}'
  [pd_cascade_fixed]='attitude={plugin="pd_cascade", damping="euler_rates", allocation="roll_pitch_first"}'
  [geometric]='attitude={plugin="geometric"}'
)
mkdir -p "$out"
for e in exp1_exponential exp2 exp3; do
  for p in pd_cascade pd_cascade_fixed geometric; do
    # A refused configuration is a row of the map, not a failure of the script.
    "$bin" sweep "$root/experiments/$e.toml" --set "${plugins[$p]}" --vary attitude.tilt_max=$tilts \
      --no-render --overwrite -o "$out/${e}__$p" >/dev/null || true
    echo "  swept: $out/${e}__$p"
  done
done
/usr/bin/python3 "$root/analysis/robustness_map.py" "$out"

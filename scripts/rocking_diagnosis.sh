#!/usr/bin/env bash
# "Why the vehicles rock" (docs/DISCUSSION.md): Exps 2 and 3 on the ideal point mass
# with a first-order actuation lag tau (0 .. 0.3 s; the quadrotor plugins' small-step attitude
# bandwidths give tau = 0.088 s for pd_cascade and 0.141 s for geometric), with and without an
# acceleration limit equal to the quadrotor's g tan(0.55 rad) = 6.0 m/s^2 per axis, beside the
# quadrotor with each attitude plugin. Then the table and figure (analysis/rocking_diagnosis.py).
# Usage: scripts/rocking_diagnosis.sh [OUT_DIR]   (default results/rocking; 60 runs, about 2 minutes)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# The analysis entry scripts import mjfanalysis: installed, or from the source tree (analysis/README.md).
export PYTHONPATH="$root/analysis${PYTHONPATH:+:$PYTHONPATH}"
out=${1:-$root/results/rocking}
bin=$root/build/runner/mjformation
[ -x "$bin" ] || MJF_BUILD_TARGET=mjf_product bash "$root/scripts/build.sh" "$root/build"
mkdir -p "$out/models"
# The point mass of mjcf/pointmass.xml with lagged (dyntype filter) and optionally limited
# horizontal force actuators; fz keeps no limit. Mass 1 kg: N = m/s^2.
model() {  # tau limit -> path
  local tau=$1 limit=$2 path=$out/models/pointmass_tau${1}_lim${2}.xml
  local range='ctrllimited="false"'
  [ "$limit" != 0 ] && range="ctrllimited=\"true\" ctrlrange=\"-$limit $limit\""
  local dyn='dyntype="none"'
  [ "$tau" != 0 ] && dyn="dyntype=\"filter\" dynprm=\"$tau\""
  sed -e "s|<motor name=\"fx\" class=\"pm_motor\" joint=\"x\"/>|<general name=\"fx\" joint=\"x\" gainprm=\"1\" $dyn $range/>|" \
      -e "s|<motor name=\"fy\" class=\"pm_motor\" joint=\"y\"/>|<general name=\"fy\" joint=\"y\" gainprm=\"1\" $dyn $range/>|" \
      -e "s|<motor name=\"fz\" class=\"pm_motor\" joint=\"z\"/>|<general name=\"fz\" joint=\"z\" gainprm=\"1\" $dyn/>|" \
      "$root/mjcf/pointmass.xml" > "$path"
  grep -q '<general name="fx"' "$path" || { echo "rocking_diagnosis: model edit failed" >&2; exit 1; }
  echo "$path"
}
run() {  # experiment name [--set ...]
  local e=$1 name=$2
  shift 2
  "$bin" run "$root/experiments/$e.toml" --out "$out/$e/$name" --overwrite --quiet --no-render "$@" \
    || echo "  incomplete: $out/$e/$name" >&2
}
pm=(--set 'attitude={plugin="pointmass_direct"}')
for e in exp2 exp3; do
  for tau in 0 0.02 0.04 0.06 0.088 0.1 0.127 0.15 0.2 0.25 0.3; do
    run "$e" "pm_tau${tau}_lim0" --set "vehicles.model=\"$(model "$tau" 0)\"" "${pm[@]}" &
    run "$e" "pm_tau${tau}_lim6.0" --set "vehicles.model=\"$(model "$tau" 6.0)\"" "${pm[@]}"
    wait
  done
  # Authority: the point mass limited to what tilt_max 0.35 and 0.45 rad give, g tan(tilt_max)
  # per axis (a box: up to sqrt(2) more along the diagonals than the tilt's disc), first ideal.
  # Then with the two plugins' lags (0.088, 0.141 s).
  for tau in 0 0.088 0.141; do
    run "$e" "pm_tau${tau}_lim3.57" --set "vehicles.model=\"$(model "$tau" 3.57)\"" "${pm[@]}" &
    run "$e" "pm_tau${tau}_lim4.86" --set "vehicles.model=\"$(model "$tau" 4.86)\"" "${pm[@]}"
    wait
  done
  run "$e" quad_pd_cascade &
  run "$e" quad_geometric --set 'attitude={plugin="geometric", tilt_max=0.55}'
  wait
  echo "  ran: $out/$e"
done
/usr/bin/python3 "$root/analysis/rocking_diagnosis.py" "$out"

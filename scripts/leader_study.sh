#!/usr/bin/env bash
# Non-cooperative leaders: every experiment of experiments/leaders/ on the quadrotor
# and the point mass (seeded leaders with seeds 1-5), sigma_f against the sample period T
# (12 periods, 0.005-0.2 s, circle and bang_bang leaders), the theory curves of
# leader_theory_test, and the report section: RESULTS/report/leaders.md.
# Usage: scripts/leader_study.sh [--out DIR] [--jobs N] [--no-report]
#   (default DIR: results, N: 2; --no-report: runs only, for scripts/reproduce.sh, whose
#   report.py includes the same section)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# The analysis entry scripts import mjfanalysis: installed, or from the source tree (analysis/README.md).
export PYTHONPATH="$root/analysis${PYTHONPATH:+:$PYTHONPATH}"
out=$root/results
jobs=2
report=1
while (($#)); do
  case $1 in
    --out) out=$2; shift ;;
    --jobs) jobs=$2; shift ;;
    --no-report) report=0 ;;
    -h|--help) sed -n 2,8p "$0"; exit 0 ;;
    *) echo "leader_study.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done
cd "$root"  # the trajectory leader's CSV path is relative to the repository root
start=$(date +%s)
MJF_BUILD_TARGET=mjf_product bash "$root/scripts/build.sh" "$root/build"
cmake --build "$root/build" -j"$jobs" --target leader_theory_test >/dev/null
bin=$root/build/runner/mjformation
pointmass=(--set 'vehicles.model="pointmass"' --set 'attitude={plugin="pointmass_direct"}')
mkdir -p "$out/leaders" "$out/period_sweep"

# One run: experiment file, run name, extra arguments.
run_one() {
  local file=$1 name=$2
  shift 2
  if "$bin" run "$file" --out "$out/leaders/$name" --overwrite --quiet --no-render \
      --set "run.name=\"$name\"" "$@"; then
    echo "  done: $name"
  else
    echo "  FAILED or incomplete: $name" >&2
    return 1
  fi
}
status=0
pids=()
queue() {  # runs "$@" in the background, at most $jobs at once
  "$@" &
  pids+=($!)
  if ((${#pids[@]} >= jobs)); then
    wait "${pids[0]}" || status=1
    pids=("${pids[@]:1}")
  fi
}
echo "leader_study: maneuvering-leader runs into $out/leaders"
for file in "$root"/experiments/leaders/*.toml; do
  base=$(basename "$file" .toml)
  seeds=(0)
  case $base in *_random_accel|*_bang_bang) seeds=(1 2 3 4 5) ;; esac
  for seed in "${seeds[@]}"; do
    name=$base
    args=()
    if [ "$seed" != 0 ]; then name=${base}_s$seed; args=(--set "leader.seed=$seed"); fi
    queue run_one "$file" "$name" "${args[@]}"
    queue run_one "$file" "${name}_pointmass" "${args[@]}" "${pointmass[@]}"
  done
done
for p in "${pids[@]}"; do wait "$p" || status=1; done

echo "leader_study: sigma_f against T into $out/period_sweep"
periods=0.005,0.007,0.01,0.014,0.02,0.028,0.04,0.05,0.07,0.1,0.14,0.2
for vehicle in pointmass quadrotor; do
  extra=()
  [ "$vehicle" = pointmass ] && extra=("${pointmass[@]}")
  "$bin" sweep "$root/experiments/exp2.toml" --vary "formation.period=$periods" \
    -o "$out/period_sweep/${vehicle}_circle" --overwrite --no-render -j "$jobs" "${extra[@]}" \
    >/dev/null || status=1
  "$bin" sweep "$root/experiments/leaders/exp2_bang_bang.toml" \
    --vary "formation.period=$periods" --vary leader.seed=1,2,3,4,5 \
    -o "$out/period_sweep/${vehicle}_bang_bang" --overwrite --no-render -j "$jobs" \
    "${extra[@]}" >/dev/null || status=1
done

echo "leader_study: theory curves (model (40)) into $out/leaders/theory_curves.txt"
"$root/build/tests/plugins/formation/leader_theory_test" \
  --gtest_filter='*CurvesLeaderOutsideTheBoundsAndMisdeclaredBounds' >"$out/leaders/theory_curves.txt" || status=1

if [ $report = 1 ]; then
  /usr/bin/python3 "$root/analysis/leader_report.py" "$out" --out "$out/report"
fi
echo "leader_study: $(( $(date +%s) - start )) s in all"
exit $status

#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# The timing study (issue 19, reduced grid): Exp 2 (T = 0.05 s) and Exp 3 (T = 0.2 s) on the
# point mass, per-agent smc_discrete_agent with the central solve and Jacobi m = 3, receiver-side
# prediction {none, input} x link latency (9 values from 0 to just under T, a message every step,
# in-phase clocks, no loss), against central mode. N seeds per cell, start positions jittered by
# 0.5 m per seed. Then analysis/timing_study.py writes the table (largest latency within 1.5x
# central sigma_f beside the predicted margin). Restartable (--resume).
# Usage: scripts/study_timing.sh [seeds (3)] [out (runs/study_timing)] [jobs (2)]
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-3}
out=${2:-runs/study_timing}
jobs=${3:-2}
exe=${MJFORMATION:-build/runner/mjformation}
export PYTHONPATH="$PWD/analysis${PYTHONPATH:+:$PYTHONPATH}"
exec_grid='execution={mode="per_agent",coupling="central_solve",predict="none"}'
exec_grid+=',{mode="per_agent",coupling="central_solve",predict="input"}'
exec_grid+=',{mode="per_agent",coupling="jacobi",jacobi_rounds=3,predict="none"}'
exec_grid+=',{mode="per_agent",coupling="jacobi",jacobi_rounds=3,predict="input"}'
declare -A latencies=(
  [exp2]="0,0.002,0.004,0.01,0.02,0.03,0.04,0.045,0.049"
  [exp3]="0,0.01,0.02,0.05,0.08,0.1,0.15,0.18,0.199")
sweep() {
  local rc=0
  "$exe" sweep "$@" --seeds "$seeds" --no-render -j "$jobs" --resume > /dev/null || rc=$?
  if [[ $rc != 0 && $rc != 3 ]]; then  # 3: some runs diverged, expected here
    echo "study_timing: mjformation sweep exited with $rc" >&2
    exit "$rc"
  fi
}
sets=(--set vehicles.start_jitter=0.5 --set 'vehicles.model="pointmass"'
      --set 'attitude={plugin="pointmass_direct"}')
for exp in exp2 exp3; do
  echo "study_timing: $exp: central mode" >&2
  sweep "experiments/$exp.toml" "${sets[@]}" -o "$out/$exp/central"
  echo "study_timing: $exp: per-agent grid" >&2
  sweep "experiments/$exp.toml" "${sets[@]}" --vary "$exec_grid" \
    --vary "network.latency=${latencies[$exp]}" -o "$out/$exp/per_agent"
done
/usr/bin/python3 analysis/timing_study.py "$out" --table "${STUDY_TABLE:-docs/timing_study_table.md}"

#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# The timing study (a reduced grid, docs/RESULTS.md "Timing" says what is left out):
# Exp 2 (T = 0.05 s) and Exp 3 (T = 0.2 s), point mass and quadrotor (the files' pd_cascade),
# per-agent smc_discrete_agent against central mode, link latency from 0 to just under T
# (9 values), start positions jittered by 0.5 m per seed, N seeds per cell.
#   in_phase:  a message every step, clocks in phase, no loss; coupling {central_solve, Jacobi
#              m = 3} x predict {none, input, attitude (quadrotor only)};
#   off_phase: a 50 Hz broadcast, follower clocks offset by U[0, T/2], loss {0, 20 %};
#              coupling {last_input, Jacobi m = 1, Jacobi m = 3} (the central solve needs every
#              row at one instant: out of phase it skips every sample) x predict {none, the
#              vehicle's: input on the point mass, attitude on the quadrotor};
#   rates:     clocks in phase, the central solve (instantaneous rounds) with the vehicle's
#              prediction, broadcast {20, 50, 100 Hz} x loss {0, 20 %};
#   off_phase_solve: the central solve with its rounds over the links (the solver gathers one
#              sample index across the clocks), clocks offset by U[0, T/2], broadcast {1 kHz,
#              50 Hz}, the vehicle's prediction.
#   rates_couplings: clocks in phase, no loss, broadcast {20, 50, 100 Hz}, coupling {last_input,
#              Jacobi m = 1, Jacobi m = 3} with the vehicle's prediction;
#   off_phase_sync, off_phase_solve_sync: off_phase (loss 0 only) and off_phase_solve with the
#              clocks synchronised ([execution] clock_sync = true: the loops sample out of phase,
#              but time stamps and prediction read the common time).
# Then analysis/timing_study.py writes the table (largest latency within 1.5x central sigma_f
# beside the predicted margin). Restartable (--resume).
# Usage: scripts/study_timing.sh [seeds (2)] [out (runs/study_timing)] [jobs (2)]
#   STUDY_VEHICLES="pointmass quadrotor" STUDY_PARTS="in_phase rates off_phase off_phase_solve
#   rates_couplings off_phase_sync off_phase_solve_sync" (the defaults)
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-2}
out=${2:-runs/study_timing}
jobs=${3:-2}
exe=${MJFORMATION:-build/runner/mjformation}
export PYTHONPATH="$PWD/analysis${PYTHONPATH:+:$PYTHONPATH}"
declare -A latencies=(
  [exp2]="0,0.002,0.004,0.01,0.02,0.03,0.04,0.045,0.049"
  [exp3]="0,0.01,0.02,0.05,0.08,0.1,0.15,0.18,0.199")
# Over the links a central-solve round takes 2L (R_i up, W_i down): refused from L = T/2 on.
declare -A solve_latencies=(
  [exp2]="0,0.002,0.004,0.01,0.015,0.02,0.024"
  [exp3]="0,0.01,0.02,0.05,0.08,0.09,0.099")
declare -A half_period=([exp2]=0.025 [exp3]=0.1)
declare -A predicts=([pointmass]="none input" [quadrotor]="none input attitude")
declare -A own_predict=([pointmass]=input [quadrotor]=attitude)
sweep() {
  local rc=0
  "$exe" sweep "$@" --seeds "$seeds" --no-render -j "$jobs" --resume > /dev/null || rc=$?
  if [[ $rc != 0 && $rc != 3 ]]; then  # 3: some runs diverged, expected here
    echo "study_timing: mjformation sweep exited with $rc" >&2
    exit "$rc"
  fi
}
# One --vary value list: [execution] tables for each coupling x predict ($2: extra keys).
exec_grid() {
  local predicts=$1 extra=$2 grid="execution=" sep=""
  for coupling in "${@:3}"; do
    for p in $predicts; do
      grid+="$sep{mode=\"per_agent\",$coupling,predict=\"$p\"$extra}"
      sep=","
    done
  done
  echo "$grid"
}
for vehicle in ${STUDY_VEHICLES:-pointmass quadrotor}; do
  sets=(--set vehicles.start_jitter=0.5)
  [ "$vehicle" = pointmass ] &&
    sets+=(--set 'vehicles.model="pointmass"' --set 'attitude={plugin="pointmass_direct"}')
  for exp in exp2 exp3; do
    dir="$out/$vehicle/$exp"
    # The reference, once: a later invocation for other parts (maybe with fewer seeds) keeps it.
    if [ ! -f "$dir/central/sweep.json" ]; then
      echo "study_timing: $vehicle $exp: central mode" >&2
      sweep "experiments/$exp.toml" "${sets[@]}" -o "$dir/central"
    fi
    for part in ${STUDY_PARTS:-in_phase rates off_phase off_phase_solve rates_couplings off_phase_sync off_phase_solve_sync}; do
      echo "study_timing: $vehicle $exp: $part" >&2
      if [ "$part" = in_phase ]; then
        grid=$(exec_grid "${predicts[$vehicle]}" "" 'coupling="central_solve"' \
          'coupling="jacobi",jacobi_rounds=3')
        sweep "experiments/$exp.toml" "${sets[@]}" --vary "$grid" \
          --vary "network.latency=${latencies[$exp]}" -o "$dir/in_phase"
      elif [ "$part" = rates ]; then
        grid=$(exec_grid "${own_predict[$vehicle]}" "" 'coupling="central_solve"')
        sweep "experiments/$exp.toml" "${sets[@]}" --vary "$grid" \
          --vary "network.rate=20.0,50.0,100.0" --vary "network.loss=0.0,0.2" \
          --vary "network.latency=${latencies[$exp]}" -o "$dir/rates"
      elif [ "$part" = rates_couplings ]; then
        grid=$(exec_grid "${own_predict[$vehicle]}" "" 'coupling="last_input"' \
          'coupling="jacobi",jacobi_rounds=1' 'coupling="jacobi",jacobi_rounds=3')
        sweep "experiments/$exp.toml" "${sets[@]}" --vary "$grid" \
          --vary "network.rate=20.0,50.0,100.0" \
          --vary "network.latency=${latencies[$exp]}" -o "$dir/rates_couplings"
      elif [ "$part" = off_phase_solve ] || [ "$part" = off_phase_solve_sync ]; then
        sync=""
        [ "$part" = off_phase_solve_sync ] && sync=",clock_sync=true"
        grid=$(exec_grid "${own_predict[$vehicle]}" ",clock_offset=${half_period[$exp]}$sync" \
          'coupling="central_solve"')
        sweep "experiments/$exp.toml" "${sets[@]}" --set 'network.rounds="over_links"' \
          --vary "$grid" --vary "network.rate=1000.0,50.0" \
          --vary "network.latency=${solve_latencies[$exp]}" -o "$dir/$part"
      elif [ "$part" = off_phase_sync ]; then
        grid=$(exec_grid "none ${own_predict[$vehicle]}" \
          ",clock_offset=${half_period[$exp]},clock_sync=true" 'coupling="last_input"' \
          'coupling="jacobi",jacobi_rounds=1' 'coupling="jacobi",jacobi_rounds=3')
        sweep "experiments/$exp.toml" "${sets[@]}" --set network.rate=50.0 --vary "$grid" \
          --vary "network.latency=${latencies[$exp]}" -o "$dir/off_phase_sync"
      else
        grid=$(exec_grid "none ${own_predict[$vehicle]}" ",clock_offset=${half_period[$exp]}" \
          'coupling="last_input"' 'coupling="jacobi",jacobi_rounds=1' \
          'coupling="jacobi",jacobi_rounds=3')
        sweep "experiments/$exp.toml" "${sets[@]}" --set network.rate=50.0 --vary "$grid" \
          --vary "network.loss=0.0,0.2" --vary "network.latency=${latencies[$exp]}" \
          -o "$dir/off_phase"
      fi
    done
  done
done
/usr/bin/python3 analysis/timing_study.py "$out" --table "${STUDY_TABLE:-docs/timing_study_table.md}"

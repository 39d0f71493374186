#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# The distributed-execution study: Exp 2 and Exp 3 (discrete SMC) on the point mass
# and the quadrotor, every follower running its own smc_discrete_agent over the simulated
# network, per coupling of (48)'s u_j(k) loop (last received input, Jacobi m = 1 and 3, the
# host's central solve) x latency {0, 1, 2, 5, 10, 20, 50, 100 ms} (fixed, every link) x
# Bernoulli loss {0, 5, 20, 50 %} (every link), against central mode (the swarm-level plugin, no
# network). N seeds per cell; start positions jittered by 0.5 m per seed (as the noise x wind
# study) so that every cell, the loss-free ones included, is a sample. Then the tables and figure
# (analysis/network_study.py). Restartable: the sweeps run with --resume.
# Usage: scripts/study_network.sh [seeds (10)] [out (runs/study_network)] [jobs (2)]
set -euo pipefail
cd "$(dirname "$0")/.."
# The analysis entry scripts import mjfanalysis: installed, or from the source tree (analysis/README.md).
export PYTHONPATH="$PWD/analysis${PYTHONPATH:+:$PYTHONPATH}"
seeds=${1:-10}
out=${2:-runs/study_network}
jobs=${3:-2}
exe=${MJFORMATION:-build/runner/mjformation}
couplings='execution={mode="per_agent",coupling="last_input"}'
couplings+=',{mode="per_agent",coupling="jacobi",jacobi_rounds=1}'
couplings+=',{mode="per_agent",coupling="jacobi",jacobi_rounds=3}'
couplings+=',{mode="per_agent",coupling="central_solve"}'
latency="network.latency=${STUDY_LATENCIES:-0,0.001,0.002,0.005,0.01,0.02,0.05,0.1}"
loss="network.loss=${STUDY_LOSSES:-0,0.05,0.2,0.5}"
# Exit 3 means the sweep ran every run and some stopped early (diverged): expected here, and
# the tables say so per cell. Anything else (bad input, an interrupt) stops the study.
sweep() {
  local rc=0
  "$exe" sweep "$@" --seeds "$seeds" --no-render -j "$jobs" --resume > /dev/null || rc=$?
  if [[ $rc != 0 && $rc != 3 ]]; then
    echo "study_network: mjformation sweep exited with $rc" >&2
    exit "$rc"
  fi
}
for vehicle in ${STUDY_VEHICLES:-pointmass quadrotor}; do
  sets=(--set vehicles.start_jitter=0.5)
  if [[ $vehicle == pointmass ]]; then
    sets+=(--set 'vehicles.model="pointmass"' --set 'attitude={plugin="pointmass_direct"}')
  fi
  for exp in ${STUDY_EXPERIMENTS:-exp2 exp3}; do
    dir="$out/$vehicle/$exp"
    echo "study_network: $vehicle $exp: central mode" >&2
    sweep "experiments/$exp.toml" "${sets[@]}" -o "$dir/central"
    echo "study_network: $vehicle $exp: per-agent grid" >&2
    sweep "experiments/$exp.toml" "${sets[@]}" --vary "$couplings" --vary "$latency" \
      --vary "$loss" -o "$dir/per_agent"
  done
done
/usr/bin/python3 analysis/network_study.py "$out" --table "${STUDY_TABLE:-docs/network_study_table.md}" \
  --figure "${STUDY_FIGURE:-docs/img/network_sigma_f.png}"

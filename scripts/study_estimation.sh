#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# The estimation study: an experiment x sensor suite {motion capture, RTK, consumer
# GNSS} x estimator {passthrough (raw held samples), kf_ins} x wind {calm, 6 m/s with moderate
# Dryden turbulence}, with the ideal suite as the reference, on the quadrotor and the point
# mass, N seeds per cell (the seed drives the sensor noise and the turbulence; the start layout
# stays: jittered starts put followers within the near-miss margin at t = 0), then the table
# (analysis/estimation_study.py: mean sigma_f with its 95 % CI per cell, complete runs, runs with
# safety events). Restartable: the sweeps run with --resume.
# Usage: scripts/study_estimation.sh [seeds (20)] [out (runs/study_estimation)] [jobs (2)]
#   STUDY_EXPERIMENTS="exp2 exp3 exp1_exponential" (default: all three)
set -euo pipefail
cd "$(dirname "$0")/.."
export PYTHONPATH="$PWD/analysis${PYTHONPATH:+:$PYTHONPATH}"
seeds=${1:-20}
out=${2:-runs/study_estimation}
jobs=${3:-2}
exe=build/runner/mjformation
suites='sensors={preset="mocap"},{preset="rtk"},{preset="consumer_gnss"}'
estimators='estimator={plugin="passthrough"},{plugin="kf_ins"}'
wind='wind={mean=[0.0,0.0,0.0]},{mean=[6.0,0.0,0.0],turbulence="moderate"}'
# A sweep exits 3 when some of its runs diverged or stopped early: that is a result of the study
# (the table counts them), not a failure of the script.
sweep() { "$exe" sweep "$@" > /dev/null || [ $? = 3 ]; }
pointmass=(--set 'vehicles.model="pointmass"' --set 'attitude={plugin="pointmass_direct"}')
for exp in ${STUDY_EXPERIMENTS:-exp2 exp3 exp1_exponential}; do
  for vehicle in quadrotor pointmass; do
    extra=()
    [ "$vehicle" = pointmass ] && extra=("${pointmass[@]}")
    common=(--seeds "$seeds" --no-render -j "$jobs" --resume "${extra[@]}")
    sweep "experiments/$exp.toml" "${common[@]}" --vary "$suites" --vary "$estimators" \
      --vary "$wind" -o "$out/$exp/$vehicle"
    # The reference: ideal sensors (no accelerometer, so no kf_ins).
    sweep "experiments/$exp.toml" "${common[@]}" --set 'sensors={preset="ideal"}' \
      --vary "$wind" -o "$out/$exp/${vehicle}_ideal"
  done
done
/usr/bin/python3 analysis/estimation_study.py "$out"

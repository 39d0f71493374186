#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# The sensor-noise x wind study: Exp 2 and Exp 3 (smc_discrete, quadrotor) under
# sensor noise {ideal, typical, 3x typical} x mean wind {0, 3, 6, 10 m/s} with moderate Dryden
# turbulence, N seeds per cell (start positions jittered by 0.5 m per seed so that every cell,
# the ideal one included, is a sample), then the table and figure (analysis/realism_study.py).
# Restartable: the sweeps run with --resume.
# Usage: scripts/study_realism.sh [seeds (20)] [out (runs/study_realism)] [jobs (2)]
set -euo pipefail
cd "$(dirname "$0")/.."
# The analysis entry scripts import mjfanalysis: installed, or from the source tree (analysis/README.md).
export PYTHONPATH="$PWD/analysis${PYTHONPATH:+:$PYTHONPATH}"
seeds=${1:-20}
out=${2:-runs/study_realism}
jobs=${3:-2}
exe=build/runner/mjformation
noise='sensors={preset="ideal"},{preset="typical"},{preset="typical",scale=3.0}'
wind='wind={turbulence="moderate"}'
for speed in 3.0 6.0 10.0; do
  wind+=",{mean=[$speed,0.0,0.0],turbulence=\"moderate\"}"
done
for exp in ${STUDY_EXPERIMENTS:-exp2 exp3}; do
  "$exe" sweep "experiments/$exp.toml" --seeds "$seeds" --no-render -j "$jobs" --resume \
    --set vehicles.start_jitter=0.5 --vary "$noise" --vary "$wind" -o "$out/$exp" > /dev/null
done
/usr/bin/python3 analysis/realism_study.py "$out" --figure docs/img/realism_study.png \
  --bands docs/img/realism_sigma_f_bands.png

#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# The 13 runs of scripts/reproduce.sh (Experiments 1-3 and the consensus baseline on both
# vehicles, and Exp 2 per agent over the network), without rendering, with a given runner binary:
# the before/after corpus of an engine change (docs/RESULTS.md, "Engine change").
#   dev/engine_runs.sh MJFORMATION OUT      # e.g. a build on the old engine, then on the new one
#   dev/engine_table.py OUT_BEFORE OUT_AFTER  # the table
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# = 2 ] || { sed -n 4,8p "$0"; exit 2; }
bin=$1 out=$2
mkdir -p "$out"
one() {
  local name=$1; shift
  if "$bin" run "$@" --out "$out/$name" --overwrite --quiet --no-render; then
    echo "  done: $name"
  else
    echo "  FAILED or incomplete: $name" >&2
  fi
}
pids=()
for e in exp1_printed exp1_switching exp1_exponential exp2 exp3 consensus_baseline; do
  one "$e" "$root/experiments/$e.toml" &
  one "${e}_pointmass" "$root/experiments/$e.toml" --set 'vehicles.model="pointmass"' \
    --set 'attitude={plugin="pointmass_direct"}' --set "run.name=\"${e}_pointmass\"" &
  wait
done
one exp2_network "$root/experiments/exp2.toml" --set 'run.name="exp2_network"' \
  --set 'execution={mode="per_agent",coupling="central_solve"}' \
  --set 'network={latency=0.001,jitter=0.001,loss=0.02,loss_model="gilbert_elliott",burst_enter=0.01,burst_exit=0.25}'

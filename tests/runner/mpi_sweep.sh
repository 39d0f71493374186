#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# `mpirun -np K mjformation sweep`: the same run directories and table bytes as the
# threaded sweep, with 3 ranks and with 1; a rank killed mid-sweep followed by --resume
# completes the sweep with the same bytes again.
# Usage: mpi_sweep.sh <mjformation> <work folder>
set -euo pipefail
exe=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
mpirun=(mpirun --allow-run-as-root --oversubscribe)
cat > "$work/e.toml" <<'TOML'
[run]
name = "hover"
duration = 3.0
[vehicles]
model = "quadrotor"
followers = 2
altitude = 2.0
leader_start = [0.0, 0.0]
start_jitter = 0.5
[topology]
leader_links = [1]
[leader]
plugin = "hover"
[formation]
plugin = "hover"
[attitude]
plugin = "pd_cascade"
[sensors]
preset = "typical"
[wind]
mean = [3.0, 0.0, 0.0]
turbulence = "light"
altitude = 5.0
TOML
base=(sweep "$work/e.toml" --vary vehicles.altitude=2.0,3.0 --no-render)
args=("${base[@]}" --seeds 3)

same() {  # same tables and timeseries in two sweep folders
  for f in sweep.csv sweep_runs.csv sweep.json; do
    cmp "$1/$f" "$2/$f" || { echo "FAIL: $f differs ($1 vs $2)"; exit 1; }
  done
  for d in "$1"/*/; do
    cmp "$d/timeseries.csv" "$2/$(basename "$d")/timeseries.csv" ||
      { echo "FAIL: $(basename "$d")/timeseries.csv differs"; exit 1; }
  done
}

"$exe" "${args[@]}" -j 2 -o "$work/threads" > /dev/null 2>&1
"${mpirun[@]}" -np 3 "$exe" "${args[@]}" -o "$work/mpi3" > "$work/mpi3.log" 2>&1
same "$work/threads" "$work/mpi3"
echo "3 ranks: same bytes as the threaded sweep"
"${mpirun[@]}" -np 1 "$exe" "${args[@]}" -o "$work/mpi1" > "$work/mpi1.log" 2>&1
same "$work/threads" "$work/mpi1"
echo "1 rank: same bytes"

# Kill rank 1 once a run has finished; Open MPI then ends the whole job.
# Longer runs (20 s) so that the kill lands mid-sweep.
long=(--seeds 6 --set run.duration=20.0)
"${mpirun[@]}" -np 3 "$exe" "${base[@]}" "${long[@]}" -o "$work/killed" > "$work/killed.log" 2>&1 &
launcher=$!
victim=""
for _ in $(seq 1 1200); do
  if ls "$work"/killed/*/summary.json > /dev/null 2>&1; then
    for pid in $(pgrep -P "$launcher"); do
      if tr '\0' '\n' < "/proc/$pid/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
        victim=$pid
      fi
    done
    [ -n "$victim" ] && break
  fi
  kill -0 "$launcher" 2> /dev/null || break
  sleep 0.05
done
[ -n "$victim" ] || { echo "FAIL: no rank 1 to kill"; exit 1; }
kill -9 "$victim"
if wait "$launcher"; then echo "FAIL: the job survived a killed rank"; exit 1; fi
if [ -f "$work/killed/sweep.json" ] && grep -q '^  "complete": true' "$work/killed/sweep.json"; then
  echo "FAIL: a sweep that lost a rank says it is complete"
  exit 1
fi
done_before=$(ls "$work"/killed/*/summary.json | wc -l)
"${mpirun[@]}" -np 3 "$exe" "${base[@]}" "${long[@]}" -o "$work/killed" --resume \
  > "$work/resumed.log" 2>&1
"$exe" "${base[@]}" "${long[@]}" -j 2 -o "$work/threads6" > /dev/null 2>&1
same "$work/threads6" "$work/killed"
echo "killed rank + --resume: complete, same bytes ($done_before runs kept from before)"
grep "resuming" "$work/resumed.log"

#!/usr/bin/env bash
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# "Ideal by default, byte for byte" (DEVELOPERS.md): runs a fixed corpus of short runs that
# together exercise every stage of the tick (both vehicles and rotor models, both attitude
# plugins, per-agent execution over a lossy network with prediction and clocks out of phase,
# sensors and an estimator, wind, partitioned physics, a maneuvering leader), then compares it
# with a corpus made earlier by another binary.
#   dev/bytecheck.sh make MJFORMATION OUT          # run the corpus with that binary into OUT
#   dev/bytecheck.sh compare OUT_BEFORE OUT_AFTER  # timeseries.csv and exit codes: cmp;
#                                                  # summary.json: equal but for timing fields
# Exit status of compare: 0 every case identical, 1 a difference (each one named).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

# name|experiment|--set overrides (separated by ';')
CASES=(
  "exp1|experiments/exp1_exponential.toml|run.duration=4.0;run.metric_window=[2.0,4.0]"
  "exp2|experiments/exp2.toml|run.duration=4.0;run.metric_window=[2.0,4.0]"
  "exp3|experiments/exp3.toml|run.duration=4.0;run.metric_window=[2.0,4.0]"
  "exp2_geometric|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];attitude={plugin=\"geometric\"}"
  "exp2_pointmass|experiments/exp2.toml|run.duration=4.0;run.metric_window=[2.0,4.0];vehicles.model=\"pointmass\";attitude={plugin=\"pointmass_direct\"}"
  "exp2_wrench|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];vehicles.rotor_model=\"wrench\";vehicles.contacts=false"
  "exp2_threads|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];run.threads=2"
  "exp2_wrench_threads|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];vehicles.rotor_model=\"wrench\";vehicles.contacts=false;run.threads=2"
  "exp2_per_agent|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];execution={mode=\"per_agent\",coupling=\"central_solve\",predict=\"attitude\"};network={latency=0.01,loss=0.05}"
  "exp2_pm_jacobi|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];vehicles.model=\"pointmass\";attitude={plugin=\"pointmass_direct\"};execution={mode=\"per_agent\",coupling=\"jacobi\",jacobi_rounds=3,predict=\"input\",clock_offset=0.02};network={latency=0.005,loss=0.2,rate=50.0}"
  "exp2_pm_over_links|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];vehicles.model=\"pointmass\";attitude={plugin=\"pointmass_direct\"};execution={mode=\"per_agent\",coupling=\"central_solve\",predict=\"input\",clock_offset=0.02};network={latency=0.004,rounds=\"over_links\"}"
  "exp2_pm_solve_ideal|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];vehicles.model=\"pointmass\";attitude={plugin=\"pointmass_direct\"};execution={mode=\"per_agent\",coupling=\"central_solve\",predict=\"input\"};network={latency=0.02}"
  "exp3_quad_jacobi_rates|experiments/exp3.toml|run.duration=4.0;run.metric_window=[2.0,4.0];execution={mode=\"per_agent\",coupling=\"jacobi\",jacobi_rounds=1,predict=\"attitude\"};network={rate=50.0,latency=0.03,jitter=0.005}"
  "exp2_gnss_kf|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];sensors={preset=\"consumer_gnss\"};estimator={plugin=\"kf_ins\"}"
  "exp2_wind|experiments/exp2.toml|run.duration=3.0;run.metric_window=[1.5,3.0];vehicles.start_jitter=0.5;wind={mean=[2.0,0.0,0.0],turbulence=\"moderate\"}"
  "exp3_bang_bang|experiments/leaders/exp3_bang_bang.toml|run.duration=3.0;run.metric_window=[1.5,3.0]"
  "hover|experiments/hover.toml|run.duration=2.0;run.metric_window=[1.0,2.0]"
)

make_corpus() {
  local exe=$1 out=$2
  mkdir -p "$out"
  for case in "${CASES[@]}"; do
    IFS='|' read -r name exp sets <<<"$case"
    local args=()
    IFS=';' read -ra kv <<<"$sets"
    for s in "${kv[@]}"; do args+=(--set "$s"); done
    rm -rf "${out:?}/$name"
    local rc=0
    (cd "$root" && "$exe" run "$exp" "${args[@]}" --no-render -q -o "$out/$name") \
      >"$out/$name.log" 2>&1 || rc=$?
    echo "$rc" >"$out/$name.rc"
    echo "bytecheck: $name exit $rc" >&2
  done
}

# summary.json without the wall-clock fields (they differ between any two runs).
strip_timing() {
  /usr/bin/python3 - "$1" <<'EOF'
import json, sys
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items()
                if k not in ("timing", "wall_s", "started", "finished", "host", "command_line")}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o
print(json.dumps(strip(json.load(open(sys.argv[1]))), sort_keys=True))
EOF
}

compare_corpus() {
  local a=$1 b=$2 bad=0
  for case in "${CASES[@]}"; do
    local name=${case%%|*}
    if ! cmp -s "$a/$name.rc" "$b/$name.rc"; then
      echo "DIFF $name: exit $(cat "$a/$name.rc") -> $(cat "$b/$name.rc")"; bad=1; continue
    fi
    if ! cmp -s "$a/$name/timeseries.csv" "$b/$name/timeseries.csv"; then
      echo "DIFF $name: timeseries.csv"; bad=1
    fi
    if [ -f "$a/$name/summary.json" ] &&
        [ "$(strip_timing "$a/$name/summary.json")" != "$(strip_timing "$b/$name/summary.json")" ]; then
      echo "DIFF $name: summary.json (timing aside)"; bad=1
    fi
  done
  [ $bad = 0 ] && echo "bytecheck: ${#CASES[@]} cases identical"
  return $bad
}

case ${1:-} in
  make) make_corpus "$(realpath "$2")" "$(realpath -m "$3")" ;;
  compare) compare_corpus "$2" "$3" ;;
  *) sed -n '4,11p' "$0" >&2; exit 2 ;;
esac

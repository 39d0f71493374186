#!/usr/bin/env bash
# Fuzzes every parser of outside input with libFuzzer (docs/FUZZING.md): builds the targets of
# tests/fuzz in the instrumented tree that dev/test.sh also tests (dev/sanitizer_build.sh: Clang,
# ASan and UBSan), then runs each from its checked-in seeds and regression inputs for SECONDS. New
# inputs and any finding (crash-*, leak-*, timeout-*, oom-*) go under
# BUILD/tests/fuzz/work/<target>/; nothing in the source tree is written. Exit 1 when any target
# found something.
# Usage: dev/fuzz.sh [--seconds N] [--build DIR] [TARGET...]
#   TARGET: experiment vehicle_mjcf timeseries trajectory sweep_vary native_config
#           exported_scene (default: all)
#   --seconds N: per target (default 900, the once-per-change long run; the test suite's
#                fuzz_run_* tests run 15 s each: MJF_FUZZ_SECONDS)
#   --build DIR: the instrumented tree (default build-asan)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=900 build=$root/build-asan targets=()
while (($#)); do
  case $1 in
    --seconds) seconds=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    -h|--help) sed -n 2,13p "$0"; exit 0 ;;
    *) targets+=("$1"); shift ;;
  esac
done
((${#targets[@]})) || targets=(experiment vehicle_mjcf timeseries trajectory sweep_vary native_config
                                  exported_scene)
target_args=()
for t in "${targets[@]}"; do target_args+=(--target "fuzz_$t"); done
bash "$root/dev/sanitizer_build.sh" "$build" --fuzz-seconds "$seconds" "${target_args[@]}"
found=0
for t in "${targets[@]}"; do
  echo "== fuzz_$t for $seconds s"
  # The same command as the test fuzz_run_$t; leaks are checked (Mesa is not loaded here).
  if ! (cd "$build" && ASAN_OPTIONS=detect_leaks=1 ctest -R "^fuzz_run_$t\$" --output-on-failure \
        --timeout $((seconds + 300)) | tail -n 25); then
    found=1
  fi
  # What the run did: executions, coverage at the start and the end, peak memory.
  grep -E 'INITED|DONE|stat::number_of_executed_units|stat::peak_rss_mb' \
    "$build/Testing/Temporary/LastTest.log" || true
  ls "$build/tests/fuzz/work/$t/" | grep -E '^(crash|leak|timeout|oom|slow-unit)-' || true
done
exit $found

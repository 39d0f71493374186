#!/usr/bin/env bash
# Configures and builds the one instrumented tree: Clang with AddressSanitizer + UBSan, every test,
# and the fuzz targets as libFuzzer binaries (every library compiled with -fsanitize=fuzzer-no-link,
# so libFuzzer sees the parsers' coverage). dev/test.sh runs the whole suite in it (the fuzz_run_*
# tests included) and dev/fuzz.sh its long fuzz runs, so nothing is built twice. Clang, not GCC:
# it compiles the instrumented code about 2.5 times faster, and libFuzzer needs it.
# Usage: dev/sanitizer_build.sh [BUILD_DIR] [--fuzz-seconds N] [--target T]... [cmake arguments...]
#   BUILD_DIR default: build-asan. --fuzz-seconds: what each fuzz_run_<name> test runs (default 15).
#   --target: build only T and what it needs (default: everything).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-asan
if (($#)) && [[ $1 != -* ]]; then build=$1; shift; fi
seconds=15
targets=()
while (($#)); do
  case $1 in
    --fuzz-seconds) seconds=$2; shift 2 ;;
    --target) targets+=(--target "$2"); shift 2 ;;
    *) break ;;
  esac
done
command -v clang++ >/dev/null ||
  { echo "sanitizer_build.sh: clang++ is missing: bash scripts/setup.sh installs it" >&2; exit 1; }
# Line tables are all a sanitizer report needs (file:line in every frame); full debug info costs
# about an eighth more compile time.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DMJF_SANITIZE=ON -DMJF_FUZZ=ON \
  -DMJF_FUZZ_SECONDS="$seconds" \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" -DCMAKE_C_FLAGS="-fsanitize=fuzzer-no-link" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  ${MJF_PYTHON_ENV:+-DMJF_PYTHON_ENV="$MJF_PYTHON_ENV"} "$@" >/dev/null
# The build runs each test binary once to list its tests (gtest_discover_tests); LeakSanitizer
# checks that run too, so it takes the same suppressions as the tests (Mesa's and LLVM's
# allocations at load, tests/lsan.supp).
export LSAN_OPTIONS="suppressions=$root/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
cmake --build "$build" -j"$(nproc)" "${targets[@]}"

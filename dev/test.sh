#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (scripts/test.sh forwards here), in two
# trees, each built once:
#   1. the release build (GCC, what users run): the tests of the product as a user meets it, the
#      README's commands, the Python module and `pip install .`, the analysis and the lint checks
#      (MJF_UNIT_TESTS=OFF: its C++ tests are not built here);
#   2. the instrumented build (Clang, ASan + UBSan, dev/sanitizer_build.sh): every C++ test and
#      every command-line test, with leak checking (Mesa's own leak suppressed: tests/lsan.supp),
#      and the fuzz targets' short runs (fuzz_run_*, MJF_FUZZ_SECONDS each, default 15;
#      docs/FUZZING.md). Each test runs once, in the build that checks the most.
# Prints the time of each phase and the total in its closing line.
# Set MJF_SKIP_SANITIZE=1 to skip the instrumented tree (the release tree then runs every test),
# MJF_SKIP_FUZZ=1 to skip the fuzz runs, MJF_SANITIZE_TESTS=REGEX to run only the matching tests
# there.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
phases=()
phase_start=$SECONDS
end_phase() {  # NAME: records how long the phase that ends now took
  phases+=("$1 $((SECONDS - phase_start)) s")
  echo "== $1: $((SECONDS - phase_start)) s"
  phase_start=$SECONDS
}
# A test suite whose set-up failed reports its tests as skipped, and ctest passes: not here.
run_ctest() {  # BUILD_DIR NAME [ctest arguments...]
  local build=$1 name=$2 log
  shift 2
  log=$(mktemp)
  (cd "$build" && ctest --output-on-failure -j2 "$@") | tee "$log"
  if grep -q '\*\*\*Skipped' "$log"; then
    echo "test.sh: tests were skipped in the $name build (a failed set-up?):" >&2
    grep '\*\*\*Skipped' "$log" >&2
    exit 1
  fi
  rm -f "$log"
}

# Without the instrumented tree, the release tree builds and runs the C++ tests itself.
unit_tests=OFF
[ "${MJF_SKIP_SANITIZE:-0}" = 1 ] && unit_tests=ON
MJF_UNIT_TESTS=$unit_tests bash "$root/scripts/build.sh" "$root/build"
end_phase "release build"
run_ctest "$root/build" release
end_phase "release tests"
if [ "${MJF_SKIP_SANITIZE:-0}" != 1 ]; then
  echo "== instrumented build (Clang, ASan + UBSan, fuzz targets)"
  bash "$root/dev/sanitizer_build.sh" "$root/build-asan" --fuzz-seconds "${MJF_FUZZ_SECONDS:-15}"
  end_phase "instrumented build"
  skip_fuzz=()
  [ "${MJF_SKIP_FUZZ:-0}" = 1 ] && skip_fuzz=(-LE fuzz)
  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$root/tests/lsan.supp" \
    run_ctest "$root/build-asan" instrumented -R "${MJF_SANITIZE_TESTS:-.}" "${skip_fuzz[@]}"
  end_phase "instrumented tests and fuzz runs"
fi
echo "test.sh: phases: $(IFS=';'; echo "${phases[*]}" | sed 's/;/, /g')"
echo "test.sh: every test passed (${SECONDS} s)"

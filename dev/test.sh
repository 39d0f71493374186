#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (scripts/test.sh forwards here): the C++
# suites and the analysis pytest (through ctest), then all of them again under AddressSanitizer + UBSan.
# Set MJF_SKIP_SANITIZE=1 to skip the sanitizer build, MJF_SKIP_FUZZ=1 to skip the short fuzz runs
# (dev/fuzz.sh, MJF_FUZZ_SECONDS per target, default 15).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh" "$root/build"
log=$(mktemp)
(cd "$root/build" && ctest --output-on-failure -j2) | tee "$log"
# A test suite whose set-up failed reports its tests as skipped, and ctest passes: not here.
if grep -q '\*\*\*Skipped' "$log"; then
  echo "test.sh: tests were skipped in the regular build (a failed set-up?):" >&2
  grep '\*\*\*Skipped' "$log" >&2
  exit 1
fi
rm -f "$log"
if [ "${MJF_SKIP_SANITIZE:-0}" != 1 ]; then
  echo "== sanitizer build (ASan + UBSan)"
  cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMJF_SANITIZE=ON >/dev/null
  cmake --build "$root/build-asan" -j"$(nproc)"
  # Every test again, with leak checking (Mesa's own leak suppressed: tests/lsan.supp).
  (cd "$root/build-asan" && ASAN_OPTIONS=detect_leaks=1 \
      LSAN_OPTIONS="suppressions=$root/tests/lsan.supp" ctest --output-on-failure -j2 \
      -R "${MJF_SANITIZE_TESTS:-.}")
fi
if [ "${MJF_SKIP_FUZZ:-0}" != 1 ]; then
  # A short run of every fuzz target from its checked-in corpus (docs/FUZZING.md).
  echo "== fuzz targets, ${MJF_FUZZ_SECONDS:-15} s each (libFuzzer, Clang)"
  bash "$root/dev/fuzz.sh" --seconds "${MJF_FUZZ_SECONDS:-15}"
fi
echo "test.sh: every test passed (${SECONDS} s)"

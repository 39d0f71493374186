#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh) and builds mjformation.
# Usage: scripts/build.sh [BUILD_DIR] [extra cmake arguments...]   (default BUILD_DIR: build)
# Environment: MJF_BUILD_TARGET=<target> builds only that target (and what it depends on);
# MJF_UNIT_TESTS=OFF leaves out the C++ tests (default ON; CMakeLists.txt).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true
bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release ${MJF_PYTHON_ENV:+-DMJF_PYTHON_ENV="$MJF_PYTHON_ENV"} \
  -DMJF_UNIT_TESTS="${MJF_UNIT_TESTS:-ON}" "$@" >/dev/null
# MJF_BUILD_TARGET=mjf_product builds what the README uses and cmake --install installs (no tests).
cmake --build "$build" -j"$(nproc)" ${MJF_BUILD_TARGET:+--target "$MJF_BUILD_TARGET"}

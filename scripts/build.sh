#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh) and builds mjformation.
# Usage: scripts/build.sh [BUILD_DIR] [extra cmake arguments...]   (default BUILD_DIR: build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true
bash "$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"

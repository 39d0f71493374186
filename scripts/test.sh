#!/usr/bin/env bash
# Runs every test (the README's command): forwards to dev/test.sh, where the developer tools live.
set -euo pipefail
exec bash "$(cd "$(dirname "$0")/.." && pwd)/dev/test.sh" "$@"

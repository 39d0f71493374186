#!/usr/bin/env bash
# Checks that every C and C++ file of the repository is formatted by .clang-format (ctest runs it
# as clang_format). Prints each file that clang-format would change and exits 1; `--fix` formats
# them in place instead. The files are those git tracks, or every source under the root outside a
# git checkout; build trees and the project environment are never read.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
fix=0
[ "${1:-}" = --fix ] && fix=1
command -v clang-format >/dev/null ||
  { echo "format_check.sh: clang-format is missing: bash scripts/setup.sh installs it" >&2; exit 1; }
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.c' '*.cc' '*.h' '*.hpp')
else
  mapfile -t files < <(find . \( -path ./.venv -o -path './build*' \) -prune -o -type f \
    \( -name '*.c' -o -name '*.cc' -o -name '*.h' -o -name '*.hpp' \) -print | sort)
fi
if ((fix)); then
  clang-format -i "${files[@]}"
  exit 0
fi
# One clang-format for all files; each complaint starts with "FILE:LINE:COLUMN: error:".
mapfile -t bad < <(clang-format --dry-run --Werror "${files[@]}" 2>&1 |
  sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: .*/\1/p' | sort -u)
if ((${#bad[@]})); then
  echo "format_check.sh: ${#bad[@]} file(s) not formatted by .clang-format (dev/format_check.sh --fix):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "format_check.sh: ${#files[@]} files formatted"

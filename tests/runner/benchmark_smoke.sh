#!/usr/bin/env bash
# `mjformation benchmark` as a user runs it, in seconds: two laws x two scenarios x one seed on
# 2 s flights; the same command again flies nothing (resumed); then `--law` places the C law of
# examples/plugin on that board, with the board's seeds and overrides, and so does the Python law
# of examples/python.
# Usage: benchmark_smoke.sh MJFORMATION PLUGIN_DIR WORK_DIR
set -euo pipefail
trap 'echo "benchmark_smoke.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
bin=$1 plugins=$2 work=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work" && mkdir -p "$work"
board=(--laws consensus_linear,smc_discrete --scenarios b01_paper_circle,b03_random_accel
       --seeds 1 --set run.duration=2.0 --set 'run.metric_window=[1.0,2.0]' --out "$work/board")
"$bin" benchmark "${board[@]}" > "$work/board.md" 2> "$work/board.err"
grep -q "4/4 runs (0 done before)" "$work/board.err"
for f in leaderboard.md leaderboard.json leaderboard.png; do test -s "$work/board/$f"; done
python3 - "$work/board/leaderboard.json" <<'P'
import json, sys
b = json.load(open(sys.argv[1]))
assert len(b["cells"]) == 4 and len(b["runs"]) == 4, b["cells"]
assert {c["law"] for c in b["cells"]} == {"consensus_linear", "smc_discrete"}
assert all(c["failed"] or c["mean"] > 0 for c in b["cells"])
assert b["sets"] == ["run.duration=2.0", "run.metric_window=[1.0,2.0]"]
P
"$bin" benchmark "${board[@]}" > /dev/null 2> "$work/again.err"
grep -q "all 4 runs done before" "$work/again.err"
"$bin" benchmark --law example_consensus_c --plugin-path "$plugins" \
  --scenarios b01_paper_circle,b03_random_accel --baseline "$work/board/leaderboard.json" \
  --out "$work/law" > "$work/law.md" 2> "$work/law.err"
grep -q "Stored board .*benchmark version 1" "$work/law.md"
for law in consensus_linear smc_discrete example_consensus_c; do grep -q "^| \`$law\` |" "$work/law.md"; done
grep -q "2/2 runs" "$work/law.err"
# A Python law (examples/python/consensus_law.py, flown through mjformation.run) gets its row.
"$bin" benchmark --law "$root/examples/python/consensus_law.py:consensus" \
  --scenarios b01_paper_circle,b03_random_accel --baseline "$work/board/leaderboard.json" \
  --out "$work/pylaw" > "$work/pylaw.md" 2> "$work/pylaw.err"
grep -q "2/2 runs" "$work/pylaw.err"
for law in consensus_linear smc_discrete consensus; do grep -q "^| \`$law\` |" "$work/pylaw.md"; done
echo "benchmark_smoke.sh: ok"

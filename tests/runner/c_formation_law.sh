#!/usr/bin/env bash
# The plain-C formation law of examples/plugin (docs/PLUGINS.md, "A formation law"), built by
# this tree as a plugin author builds it, flown on the point mass: three followers on a one-way
# chain 1 -> 2 -> 3 (so the 0-based edges of the ABI matter: reversed, followers 2 and 3 would
# not hear anyone who hears the leader) reach their slots about a circling leader.
# Usage: c_formation_law.sh MJFORMATION PLUGIN_DIR WORK_DIR
set -euo pipefail
trap 'echo "c_formation_law.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
bin=$1 plugins=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cat > "$work/c_law.toml" <<'T'
[run]
name = "c_law"
duration = 12.0
[vehicles]
model = "pointmass"
followers = 3
altitude = 2.0
[topology]
leader_links = [1]
edges = [[1, 2], [2, 3]]
[leader]
plugin = "circle"
radius = 5.0
omega = 0.2
[formation]
plugin = "example_consensus_c"
kp = 1.0
kv = 2.0
[formation.shape]
type = "circle"
radius = 2.0
omega = 0.4
phase_step = 2.0943951023931953
[attitude]
plugin = "pointmass_direct"
T
"$bin" plugins --plugin-path "$plugins" > "$work/plugins.txt"
grep -q "example_consensus_c  -  consensus formation" "$work/plugins.txt"
"$bin" run "$work/c_law.toml" --out "$work/run" --plugin-path "$plugins" --no-render -q
python3 - "$work/run/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
m = s["metrics"] if "metrics" in s else s
assert s["complete"], s.get("error")
assert s["plugins"]["formation"]["name"] == "example_consensus_c", s["plugins"]["formation"]
initial, final = m["sigma_f_initial"], m["sigma_f_final"]
assert final < 0.05 * initial and final < 1.0, (initial, final)  # the lag of a law without u_0
print(f"example_consensus_c: sigma_f {initial:.3g} -> {final:.3g}")
PY
# A bad gain is refused with the plugin's own one-line reason.
if "$bin" check "$work/c_law.toml" --plugin-path "$plugins" --set formation.kp=-1 2>"$work/err.txt"; then
  echo "kp = -1 was accepted" >&2; exit 1
fi
grep -q "kp = '-1': expected a number > 0" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
# A law without a per-agent version in a per-agent experiment is refused with the words the
# benchmark reads as "not applicable" (analysis/mjfanalysis/benchmark.py, NO_AGENT_VERSION).
src=$(cd "$(dirname "$0")/../.." && pwd)
if "$bin" check "$src/experiments/benchmark/b13_lossy_network.toml" --plugin-path "$plugins" \
    --set 'formation={plugin="example_consensus_c"}' 2>"$work/err.txt"; then
  echo "a central-only law was accepted per agent" >&2; exit 1
fi
grep -q "'example_consensus_c' has no per-agent version" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
echo "c_formation_law: ok"

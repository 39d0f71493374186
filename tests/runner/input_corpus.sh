#!/usr/bin/env bash
# Bad input, the overwrite contract, safety events and the random sources, tried as a user would
# (docs/ARCHITECTURE.md, "Failure contract"). Each bad input must exit non-zero with
# a message that names its origin (FILE:LINE: [section] key, or "--set section.key=value"),
# write nothing, and delete nothing of the user's. Usage: input_corpus.sh BUILD_DIR WORK_DIR
set -uo pipefail
build=$(cd "$1" && pwd) work=$2
bin=$build/runner/mjformation
source=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0 passed=0
fail() { echo "FAIL [$case]: $*" >&2; failures=$((failures + 1)); }
# ok [DETAIL]: a passed case, with what the user saw (exit code and message) for the record.
ok() { echo "ok   [$case]${1:+ $1}"; passed=$((passed + 1)); }

# A small point-mass experiment: 2 followers hovering at their start, a circling leader.
cat > e.toml <<'T'
[run]
name = "e"
duration = 1.0
[vehicles]
model = "pointmass"
followers = 2
[leader]
plugin = "circle"
[formation]
plugin = "hover"
[attitude]
plugin = "pointmass_direct"
[render]
snapshots = []
T
# A user's folder and file, checked after every case.
mkdir -p mine && echo "chapter 1" > mine/thesis.txt && echo "my notes" > notes.txt
untouched() {
  [ "$(cat mine/thesis.txt)" = "chapter 1" ] && [ "$(ls -A mine)" = thesis.txt ] &&
    [ "$(cat notes.txt)" = "my notes" ]
}
# refused CODE MESSAGE -- ARGS...: exits CODE, stderr holds MESSAGE, out/ is not created.
refused() {
  local want=$1 message=$2
  shift 3
  rm -rf out
  "$bin" "$@" >/dev/null 2>err.txt
  local code=$?
  if [ "$code" != "$want" ]; then fail "exit $code, expected $want: $(head -c 400 err.txt)"
  elif ! grep -qF -- "$message" err.txt; then fail "message lacks '$message': $(head -c 400 err.txt)"
  elif [ -e out ]; then fail "out/ was created"
  elif ! untouched; then fail "the user's files changed"
  else ok "exit $code: $(grep -m1 -F -- "$message" err.txt | head -c 300)"; fi
}

# ---- the overwrite contract ----
case="sweep --overwrite on a user's folder"
refused 1 "mine: not a mjformation sweep directory" -- sweep e.toml --vary run.seed=1,2 -o mine --overwrite --no-render
case="sweep --resume on a user's folder"
refused 1 "--resume touches only sweep directories" -- sweep e.toml --vary run.seed=1,2 -o mine --resume --no-render
case="sweep -o FILE --overwrite"
refused 1 "notes.txt: exists and is not a directory" -- sweep e.toml --vary run.seed=1,2 -o notes.txt --overwrite --no-render
case="run -o FILE --overwrite"
refused 1 "notes.txt: exists and is not a directory" -- run e.toml -o notes.txt --overwrite -q
case="run.name leaving the output folder"
refused 1 '--set run.name="../../escaped": [run] name: must be a plain folder name' -- run e.toml --set 'run.name="../../escaped"' -q
[ ! -e ../../escaped ] && [ ! -e runs ] || fail "something was written for the escaping name"
case="sweep --overwrite on a sweep holding a user's file"
"$bin" sweep e.toml --vary run.seed=1,2 -o sw --no-render >/dev/null 2>&1 || fail "first sweep failed"
echo "mine" > sw/seed=1/mine.txt && echo "mine" > sw/keep.txt
"$bin" sweep e.toml --vary run.seed=1,2 -o sw --overwrite --no-render >/dev/null 2>err1.txt; c1=$?
rm sw/keep.txt
"$bin" sweep e.toml --vary run.seed=1,2 -o sw --overwrite --no-render >/dev/null 2>err2.txt; c2=$?
"$bin" sweep e.toml --vary run.seed=1,2 -o sw --resume --no-render >/dev/null 2>>err2.txt; c3=$?
[ $c1 = 1 ] && [ $c2 = 1 ] && [ $c3 = 1 ] && [ "$(cat sw/seed=1/mine.txt)" = mine ] &&
  grep -qF "refused, nothing was deleted" err1.txt && grep -qF "mine.txt" err2.txt && ok ||
  fail "exit $c1/$c2/$c3: $(cat err1.txt err2.txt)"
case="sweep --overwrite and --resume on its own sweep directory"
rm sw/seed=1/mine.txt
"$bin" sweep e.toml --vary run.seed=1,2 -o sw --overwrite --no-render >/dev/null 2>&1; c1=$?
"$bin" sweep e.toml --vary run.seed=1,2 -o sw --resume --no-render >/dev/null 2>err.txt; c2=$?
[ $c1 = 0 ] && [ $c2 = 0 ] && [ -f sw/.mjformation-sweep ] && grep -qF "2 of 2 runs done" err.txt &&
  ok || fail "exit $c1/$c2: $(cat err.txt)"

case="sweep --vary: a value valid alone but not with another axis's"
refused 1 '--vary sensors={preset="ideal"} with estimator={plugin="kf_ins"}: ' -- sweep e.toml --vary 'sensors={preset="ideal"},{preset="consumer_gnss"}' --vary 'estimator={plugin="kf_ins"}' -o out --no-render
case="sweep --vary: every combination valid though one value alone is not"
"$bin" check e.toml --set 'estimator={plugin="kf_ins"}' >/dev/null 2>&1 && fail "kf_ins alone was accepted"
"$bin" sweep e.toml --vary 'sensors={preset="rtk"},{preset="consumer_gnss"}' --vary 'estimator={plugin="passthrough"},{plugin="kf_ins"}' -o combo --no-render >/dev/null 2>err.txt; code=$?
[ $code = 0 ] && [ "$(ls -d combo/*seed* combo/*=* 2>/dev/null | wc -l)" -ge 4 ] && ok "exit 0" || fail "exit $code: $(head -c 400 err.txt)"
case="sweep prints a short summary (the table in the file) and an ETA"
"$bin" sweep e.toml --vary vehicles.altitude=2.0,3.0 --seeds 2 -o sum_sw --no-render >out.txt 2>err.txt; code=$?
[ $code = 0 ] && [ "$(wc -l < out.txt)" = 2 ] && ! grep -qF "_ci95_low" out.txt &&
  grep -qF "vehicles.altitude=3.0: sigma_f_mean" out.txt && grep -qF "ETA" err.txt &&
  [ -d "sum_sw/altitude=3.0,seed=2" ] && ok "$(head -1 out.txt)" ||
  fail "exit $code: $(cat out.txt err.txt | head -c 600)"

# ---- bounded inputs: [network] (per-agent execution) ----
net() { echo "--set execution={mode=\"per_agent\"} --set network={rate=1000.0,$1}"; }
# shellcheck disable=SC2046
for bad in "latency=1e300" "jitter=1e300" "latency=1e16" "latency=2.0"; do
  case="[network] $bad"
  refused 1 "[network] ${bad%%=*}: must be in [0, 1] s (the run's duration)" -- run e.toml -o out -q $(net "$bad")
done
cat > link.toml <<'T'
[execution]
mode = "per_agent"
[topology]
leader_links = [1]
edges = [[1, 2], [2, 1]]
[network]
rate = 1000.0
[[network.link]]
from = 1
to = 4294967297
latency = 0.01
T
cat e.toml link.toml > l.toml
case="[[network.link]] to = 4294967297"
refused 1 "l.toml:24: [network.link] to: expected a vehicle number (0: the leader, 1..2)" -- run l.toml -o out -q

# ---- bounded inputs: sweep ----
case="sweep --seeds 1e9"
refused 2 "--seeds" -- sweep e.toml --seeds 1000000000 -o out --no-render
case="sweep --seeds 1e9 (as 1e9)"
refused 2 "--seeds" -- sweep e.toml --seeds 1e9 -o out --no-render
case="sweep grid too large"
refused 1 "more than 100000 in one sweep" -- sweep e.toml --vary "run.seed=$(seq -s, 1 400)" --vary "vehicles.altitude=$(seq -s, 1 300)" -o out --no-render
case="sweep --vary unknown key"
refused 1 "--vary formation.bogus=1: " -- sweep e.toml --vary formation.bogus=1,2 -o out --no-render
case="sweep --vary a string for a number"
refused 1 "--set vehicles.altitude=\"high\": [vehicles] altitude: expected a number" -- sweep e.toml --vary 'vehicles.altitude="high"' -o out --no-render
for j in 0 -3; do
  case="sweep -j $j"
  refused 2 "--jobs" -- sweep e.toml --vary run.seed=1,2 -o out -j "$j" --no-render
done

# ---- bounded inputs: bench ----
for d in -5 nan; do
  case="bench --duration $d"
  refused 2 "--duration" -- bench e.toml --duration "$d"
done
for n in -3 0 200000; do
  case="bench --followers $n"
  refused 2 "--followers" -- bench e.toml --followers "$n"
done
case="bench leaves no run folder behind"
before=$(ls -d /tmp/mjformation_bench_* 2>/dev/null | wc -l)
"$bin" bench e.toml --duration 0.2 >/dev/null 2>err.txt; code=$?
after=$(ls -d /tmp/mjformation_bench_* 2>/dev/null | wc -l)
[ $code = 0 ] && [ "$after" -le "$before" ] && ok || fail "exit $code, /tmp folders $before -> $after"

# ---- bounded inputs: replay, view ----
"$bin" run e.toml -o rec -q --no-render || fail "recording run failed"
for bad in abc nan 1e308; do
  case="replay reads '$bad' as a position"
  rm -rf rb && cp -r rec rb
  /usr/bin/python3 - "$bad" <<'P'
import sys
rows = open("rb/timeseries.csv").read().split("\n")
head = rows[0].split(",")
cells = rows[5].split(",")
cells[head.index("uav1_px")] = sys.argv[1]
rows[5] = ",".join(cells)
open("rb/timeseries.csv", "w").write("\n".join(rows))
P
  refused 1 "rb/timeseries.csv:6: column uav1_px: '$bad' is not a finite number" -- replay rb --snapshots 0.5 -o out
done
for t in -5 1e9; do
  case="replay --snapshots $t"
  refused 1 "outside the recorded run [0, 1] s" -- replay rec --snapshots "$t" -o out
done
# replay --video-size WxH: usage errors (exit 2) naming the option and what is wrong.
for spec in "0x720:the width must be in [1, 7680]" "-5x720:the width must be in [1, 7680]" \
            "1280x0:the height must be in [1, 4320]" "abcx720:the width is not a number" \
            "1280x7e2:the height is not a number" "7681x4320:the width must be in [1, 7680] (at most 7680x4320)" \
            "1280x4321:the height must be in [1, 4320]" "1280:expected WIDTHxHEIGHT"; do
  size=${spec%%:*} message=${spec#*:}
  case="replay --video-size $size"
  refused 2 "--video-size: '$size': $message" -- replay rec --video out/v.mp4 --video-size "$size"
done
case="replay --video-size without --video"
refused 2 "--video-size requires --video" -- replay rec --video-size 640x360
for spec in "--size -100|--size: Value -100 not in range" "--bogus-flag|--bogus-flag" \
  "--set|--set: 1 required" "--speed nan|--speed must be a finite number" \
  "--speed -1|--speed: Value -1 not in range"; do
  args=${spec%%|*}
  case="view $args"
  # shellcheck disable=SC2086
  DISPLAY= refused 2 "${spec#*|}" -- view e.toml $args
done
# view --screenshot FILE writes FILE and FILE.json: neither is replaced (as replay, bench --json),
# and the refusal comes before any window, so it holds without a display.
for existing in shot.png shot.png.json; do
  case="view --screenshot onto an existing $existing"
  rm -f shot.png shot.png.json && echo "my picture" > "$existing"
  DISPLAY= refused 1 "--screenshot $existing: exists; this command never replaces a file" -- view e.toml --screenshot shot.png
  [ "$(cat "$existing")" = "my picture" ] || fail "$existing was replaced"
done

# ---- bounded inputs: [sensors], [wind], [leader], [formation], files ----
case="[sensors] scale = 1e6"
refused 1 "--set sensors.scale=1e6: [sensors] scale: must be in [0, 100]" -- run e.toml -o out -q --set 'sensors={preset="typical"}' --set sensors.scale=1e6
case="[sensors] latency longer than the run"
refused 1 "[sensors] position_latency: is longer than the run" -- run e.toml -o out -q --set 'sensors={preset="typical", position_latency=2.0}'
case="[wind] airspeed = -5 without turbulence"
refused 1 "[wind] airspeed: must be in [0.5, 100] m/s" -- run e.toml -o out -q --set 'wind={mean=[1.0,0.0,0.0], airspeed=-5.0}'
case="[wind] altitude = 1e6 without turbulence"
refused 1 "[wind] altitude: must be in [0, 1000] m" -- run e.toml -o out -q --set 'wind={mean=[1.0,0.0,0.0], altitude=1e6}'
case="[wind] gust shorter than a step"
refused 1 "duration: must be at least two physics steps" -- run e.toml -o out -q --set 'wind={mean=[1.0,0.0,0.0], gusts=[{start=0.1, duration=0.0005, amplitude=[1.0,0.0,0.0]}]}'
printf 't,x,y\n0,0,0\n1,1e300,0\n2,2,0\n' > huge.csv
case="trajectory CSV x = 1e300"
refused 1 "huge.csv:3: a value is beyond +-1e7" -- run e.toml -o out -q --set "leader={plugin=\"trajectory\", file=\"$work/huge.csv\"}"
printf 't,x,y\n0,0,0\n1,\033[31mred\033[0m,0\n' > escape.csv
case="control characters from a user's file are escaped"
refused 1 '\x1b[31mred' -- run e.toml -o out -q --set "leader={plugin=\"trajectory\", file=\"$work/escape.csv\"}"
grep -q $'\033' err.txt && fail "a raw escape byte reached the terminal"
mkdir -p afolder
case="a folder given as the trajectory file"
refused 1 "is a folder, not a CSV file" -- run e.toml -o out -q --set "leader={plugin=\"trajectory\", file=\"$work/afolder\"}"
case="a folder given as the model file"
refused 1 "is a folder" -- run e.toml -o out -q --set "vehicles.model=\"$work/afolder\""
for command in run check export; do
  case="a folder given as the experiment file ($command)"
  extra=(-o out) && [ $command = check ] && extra=()
  refused 1 "afolder: is a folder, not an experiment file" -- $command afolder "${extra[@]}"
done
case="[run] reaching_band = -0.5"
refused 1 "--set run.reaching_band=-0.5: [run] reaching_band: must be >= 0" -- run e.toml -o out -q --set run.reaching_band=-0.5
case="[run] record_rate = 1e-20 records the first and the last step, not every step"
"$bin" run e.toml -o rare -q --no-render --set run.record_rate=1e-20 2>err.txt; code=$?
[ $code = 0 ] && [ "$(tail -n +2 rare/timeseries.csv | wc -l)" = 2 ] && ok "2 rows" ||
  fail "exit $code, $(tail -n +2 rare/timeseries.csv | wc -l) rows: $(head -c 300 err.txt)"
case="a misspelt plugin name"
refused 1 "unknown plugin 'circel'; did you mean 'circle'?" -- run e.toml -o out -q --set 'leader={plugin="circel"}'
case="a misspelt command"
refused 2 "unknown command 'rnu'; did you mean 'run'? (commands: run, check" -- rnu e.toml -o out
case="formation.k = [\"3\", \"1\"]"
refused 1 '--set formation.k=["3","1"]: [formation] k: an array attribute holds numbers or booleans' -- run e.toml -o out -q --set 'formation.k=["3","1"]'
case="a self-including MJCF names the including line and the cycle"
printf '<mujoco>\n  <worldbody/>\n  <include file="self.xml"/>\n</mujoco>\n' > self.xml
refused 1 'self.xml:3: <include file="self.xml"> is an include cycle' -- run e.toml -o out -q --no-render \
  --set 'vehicles.model="self.xml"' --set 'vehicles.body="b"' --set 'vehicles.rotors=["a","b","c","d"]'
case="a vehicle model with no joint (welded to the world)"
grep -v "<freejoint" "$source/mjcf/quadrotor.xml" > welded.xml
refused 1 "welded.xml: body 'vehicle' has no joint, so it is welded to the world" -- run e.toml -o out -q --no-render \
  --set "vehicles.model=\"$work/welded.xml\"" --set 'attitude={plugin="pd_cascade"}'
case="an imu site at NaN"
sed 's|<site name="imu" pos="0 0 0"|<site name="imu" pos="nan 0 0"|' "$source/mjcf/pointmass.xml" > nan_imu.xml
refused 1 "nan_imu.xml: the site 'imu' is at nan" -- run e.toml -o out -q --no-render \
  --set "vehicles.model=\"$work/nan_imu.xml\""
case="--set with a line break (a second key smuggled in)"
refused 1 "override 'run.seed=7\\nduration=0.2': holds a line break" -- run e.toml -o out -q --set $'run.seed=7\nduration=0.2'
case="--plugin-path naming no folder"
refused 2 "/no/such" -- run e.toml -o out -q --plugin-path /no/such
case="[run] plugin_path naming no folder"
sed 's|^duration = 1.0|duration = 1.0\nplugin_path = ["no_such_plugins"]|' e.toml > pp.toml
refused 1 "pp.toml:4: [run] plugin_path: 'no_such_plugins' is not a folder" -- run pp.toml -o out -q
case="a video without ffmpeg on PATH"
rm -rf out
env PATH=/nonexistent "$bin" run e.toml -o out -q --set render.video=true --set render.snapshots=[] >/dev/null 2>err.txt; code=$?
[ $code = 1 ] && [ ! -e out ] && grep -qF "ffmpeg not found on PATH; install ffmpeg" err.txt &&
  ok "exit $code: $(head -c 300 err.txt)" || fail "exit $code, out/ $([ -e out ] && echo exists): $(head -c 300 err.txt)"
case="[vehicles] followers = 4294967297"
refused 1 "[vehicles] followers: must be in [1, 100000]" -- run e.toml -o out -q --set vehicles.followers=4294967297
case="[run] stop_on with an unknown kind"
refused 1 "[run] stop_on: expected event kinds among flip" -- run e.toml -o out -q --set 'run.stop_on=["crash"]'

# ---- safety events ----
# Followers 1 and 2 start 0.2 m apart: the point masses' spheres (0.13 m) overlap at once.
close=(--set 'vehicles.follower_start=[[0.0, 0.0], [0.2, 0.0]]')
case="a collision is reported: summary.json events and the closing line"
"$bin" run e.toml -o ev --no-render "${close[@]}" >out.txt 2>&1; code=$?
what=$(/usr/bin/python3 -c "import json; e=json.load(open('ev/summary.json'))['events']; print(e['by_kind']['collision'], e['list'][0]['vehicles'], e['list'][0]['what'])" 2>&1)
[ $code = 0 ] && grep -qF "complete; follower 1 and follower 2 collided at 0.00 s (separation 0.200 m); 1 more safety event" out.txt &&
  [ "$what" = "1 [1, 2] follower 1 and follower 2 nearly collided at 0.00 s (separation 0.200 m, -0.060 m between their bounding spheres)" ] &&
  ok || fail "exit $code: $(cat out.txt) / $what"
case="--no-render skips the render-only check of snapshot times (run and sweep)"
# Snapshots at 0.5 s and 5 s in a 1 s run: refused when rendering, accepted with --no-render.
snap=(--set 'render.snapshots=[0.5, 5.0]')
"$bin" run e.toml -o nr_run -q --no-render "${snap[@]}" 2>err.txt; code_run=$?
"$bin" sweep e.toml --vary run.seed=1,2 -o nr_sweep --no-render "${snap[@]}" >/dev/null 2>>err.txt; code_sweep=$?
"$bin" run e.toml -o r_run -q "${snap[@]}" 2>refused.txt; code_render=$?
[ $code_run = 0 ] && [ $code_sweep = 0 ] && [ $code_render = 1 ] && [ ! -e r_run ] &&
  grep -qF "[render] snapshots: times must lie in [0, duration]" refused.txt &&
  ok "with rendering: exit $code_render: $(head -c 200 refused.txt)" ||
  fail "run $code_run, sweep $code_sweep, rendering $code_render: $(head -c 300 err.txt) $(head -c 300 refused.txt)"
case="the stress experiment reports its flip, not the near miss before it"
# Random-accel leader, typical sensors, 4 m/s wind with moderate turbulence and a gust, per-agent
# Jacobi over a 20 ms bursty network; seed 2: near misses from 3 s, follower 1 flips at 36.71 s.
"$bin" run "$source/experiments/leaders/exp2_random_accel.toml" -o stress --no-render --set run.seed=2 \
  --set 'sensors={preset="typical"}' --set 'execution={mode="per_agent", coupling="jacobi"}' \
  --set 'wind={mean=[4.0,0.0,0.0], turbulence="moderate", gusts=[{start=20.0, duration=2.0, amplitude=[3.0,0.0,0.0]}]}' \
  --set 'network={latency=0.02, loss_model="gilbert_elliott", burst_enter=0.03, burst_exit=0.25}' >out.txt 2>&1
code=$?
flips=$(/usr/bin/python3 -c "import json; print(json.load(open('stress/summary.json'))['events']['by_kind']['flip'])" 2>&1)
[ $code = 0 ] && grep -qE "complete; follower [0-9]+ flipped at [0-9.]+ s" out.txt && [ "$flips" -ge 1 ] 2>/dev/null &&
  ok "$(grep -oE 'complete; follower [0-9]+ flipped at [0-9.]+ s[^,]*' out.txt)" || fail "exit $code: $(tail -c 400 out.txt) / flips $flips"
case="an event-free run has no events key"
"$bin" run e.toml -o noev -q --no-render; code=$?
/usr/bin/python3 -c "import json,sys; sys.exit('events' in json.load(open('noev/summary.json')))" && [ $code = 0 ] &&
  ok || fail "exit $code"
case="[run] stop_on ends the run at the event, exit 3"
"$bin" run e.toml -o stop -q --no-render "${close[@]}" --set 'run.stop_on=["collision"]' 2>err.txt; code=$?
reason=$(/usr/bin/python3 -c "import json; s=json.load(open('stop/summary.json')); print(s['complete'], s['error'])")
[ $code = 3 ] && [ "$reason" = "False stopped at a safety event ([run] stop_on): follower 1 and follower 2 collided at 0.00 s (separation 0.200 m)" ] &&
  [ -s stop/timeseries.csv ] && ok || fail "exit $code: $reason"
case="a sweep separates runs with events"
"$bin" sweep e.toml --vary 'vehicles.follower_start=[[0.0, 0.0], [0.2, 0.0]],[[0.0, 0.0], [3.0, 0.0]]' \
  --seeds 2 -o swev --no-render >/dev/null 2>&1; code=$?
rows=$(cut -d, -f1-8 swev/sweep.csv | tr -d '"' | tr '\n' '|')
[ $code = 0 ] && head -1 swev/sweep.csv | grep -qF "seeds,runs_with_safety_events,runs_left_out,statistics_over,runs" &&
  [ "$(grep -c ',all_complete_runs,' swev/sweep.csv)" = 2 ] && [ "$(grep -c ',valid_runs,' swev/sweep.csv)" = 2 ] &&
  grep -qF ',2,2,2,valid_runs,0,' swev/sweep.csv && grep -qF ',2,0,0,valid_runs,2,' swev/sweep.csv &&
  head -1 swev/sweep_runs.csv | grep -qF "safety_events,first_safety_event" &&
  ok || fail "exit $code: $rows"

# ---- every random source follows run.seed ----
leader_x() { tail -n 1 "$1/timeseries.csv" | cut -d, -f"$(head -1 "$1/timeseries.csv" | tr ',' '\n' | grep -n '^uav0_px$' | cut -d: -f1)"; }
ra=(--set 'leader={plugin="random_accel", a_min=-1.0, a_max=1.0, speed_max=3.0}' --set run.duration=6.0)
case="two run.seeds give two leader paths (random_accel, seed not pinned)"
"$bin" run e.toml -o s1 -q --no-render "${ra[@]}" --set run.seed=1 &&
  "$bin" run e.toml -o s1b -q --no-render "${ra[@]}" --set run.seed=1 &&
  "$bin" run e.toml -o s2 -q --no-render "${ra[@]}" --set run.seed=2; code=$?
[ $code = 0 ] && [ "$(leader_x s1)" = "$(leader_x s1b)" ] && [ "$(leader_x s1)" != "$(leader_x s2)" ] &&
  [ "$(/usr/bin/python3 -c "import json; print(json.load(open('s2/summary.json'))['plugins']['leader']['attributes']['seed'])")" = 2 ] &&
  ok || fail "exit $code, leader x: $(leader_x s1) $(leader_x s1b) $(leader_x s2)"
case="a pinned plugin seed stays, and the sweep says so"
"$bin" run e.toml -o p2 -q --no-render "${ra[@]}" --set leader.seed=1 --set run.seed=2 &&
  "$bin" sweep e.toml -o swp --no-render --seeds 2 "${ra[@]}" --set leader.seed=1 >/dev/null 2>err.txt; code=$?
[ $code = 0 ] && [ "$(leader_x s1)" = "$(leader_x p2)" ] && grep -qF "[leader] seed = 1 is pinned" err.txt &&
  ok || fail "exit $code: $(cat err.txt)"

echo "input corpus: $passed passed, $failures failed"
[ $failures = 0 ]

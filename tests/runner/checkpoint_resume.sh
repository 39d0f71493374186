#!/usr/bin/env bash
# run --checkpoint-every / --resume as a user meets them (docs/ARCHITECTURE.md, "Checkpoint and
# resume"): a run killed with SIGKILL after a checkpoint (MJF_TEST_KILL_AT_STEP: the runner
# kills itself at that step, so the place is deterministic), with rows past the checkpoint left
# in timeseries.csv, then resumed, ends with every file byte for byte as an uninterrupted
# run's (summary.json apart from its timing); a resume with another configuration is refused
# naming both hashes and changes nothing.
# Usage: checkpoint_resume.sh MJFORMATION SOURCE_DIR WORK_DIR
set -uo pipefail
bin=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL [$case]: $*" >&2; failures=$((failures + 1)); }
ok() { echo "ok   [$case]"; }
short=(--set run.duration=2 --set 'run.metric_window=[1, 2]' -q)
untimed() { grep -v '"wall_time_s"\|"real_time_factor"\|"steps_per_second"\|_wall_s"' "$1"; }

# Kill after the checkpoint at 1.0 s (step 1300 of 2000), leave a torn row, resume, compare.
resumed_equals_uninterrupted() {  # experiment, then extra arguments
  local exp=$1 && shift
  "$bin" run "$exp" "${short[@]}" "$@" --out full >/dev/null || { fail "uninterrupted run"; return; }
  MJF_TEST_KILL_AT_STEP=1300 "$bin" run "$exp" "${short[@]}" "$@" --out killed \
    --checkpoint-every 0.5 2>/dev/null
  local code=$?
  [ $code = 137 ] || { fail "the killed run exited $code, not 137 (SIGKILL)"; return; }
  [ -f killed/summary.json ] && fail "a killed run has a summary.json"
  printf '1.23,torn row' >>killed/timeseries.csv
  "$bin" run "$exp" "${short[@]}" "$@" --out killed --checkpoint-every 0.5 --resume ||
    { fail "resume exited $?"; return; }
  local f same=1
  for f in $(cd full && find . -type f ! -name summary.json); do
    cmp -s "full/$f" "killed/$f" || { fail "$f differs from the uninterrupted run's"; same=0; }
  done
  cmp -s <(untimed full/summary.json) <(untimed killed/summary.json) ||
    { fail "summary.json differs from the uninterrupted run's"; same=0; }
  [ $same = 1 ] && ok
}

case=exp2
resumed_equals_uninterrupted "$src/experiments/exp2.toml" --no-render
rm -rf full killed
case="wrench rotors, seeded random leader, snapshots on both sides of the checkpoint"
resumed_equals_uninterrupted "$src/experiments/leaders/exp2_random_accel.toml" \
  --set 'vehicles.rotor_model="wrench"' --set 'render.snapshots=[0.4, 1.8]' \
  --set render.width=64 --set render.height=48

rm -rf full killed
case="per-agent execution over a lossy network (b13: links' streams, messages in flight)"
resumed_equals_uninterrupted "$src/experiments/benchmark/b13_lossy_network.toml" --no-render

rm -rf full killed
case="Jacobi rounds, prediction, clock offsets, jitter, bursts and a range limit (its events)"
resumed_equals_uninterrupted "$src/experiments/benchmark/b13_lossy_network.toml" --no-render \
  --set 'execution={mode="per_agent", coupling="jacobi", jacobi_rounds=2, predict="input", clock_offset=0.004, clock_drift_ppm=50.0}' \
  --set 'network={rate=100.0, latency=0.02, jitter=0.005, loss=0.05, loss_model="gilbert_elliott", burst_enter=0.1, burst_exit=0.5, range=15.0}'

rm -rf full killed
case="partitioned physics (two threads: each partition's MuJoCo state and motor lags)"
resumed_equals_uninterrupted "$src/experiments/exp2.toml" --no-render --threads 2 \
  --set 'vehicles.rotor_model="wrench"'

rm -rf full killed
case="topology switches on both sides of the checkpoint (every switch's law instance saved)"
resumed_equals_uninterrupted "$src/experiments/benchmark/b07_switching_topology.toml" --no-render \
  --set 'topology.switch=[{at=0.7, leader_links=[4], edges=[[4, 5], [5, 6], [6, 1], [1, 2], [2, 3]]}, {at=1.6, leader_links=[1], edges=[[1, 2], [2, 1], [2, 3], [3, 2], [3, 4], [4, 3], [4, 5], [5, 4], [5, 6], [6, 5], [6, 1], [1, 6]]}]'

rm -rf full killed
case="a rotor fault before the checkpoint on the wrench rotor model (the faulted motor lags)"
resumed_equals_uninterrupted "$src/experiments/benchmark/b08_rotor_fault.toml" --no-render \
  --set 'vehicles.rotor_model="wrench"' \
  --set 'vehicles.fault=[{follower=3, rotor=0, at=0.6, thrust_share=0.5}]'

rm -rf full killed
case="sensors (noise, bias, latency, rate hold), the kf_ins estimator and wind saved"
resumed_equals_uninterrupted "$src/experiments/exp2.toml" --no-render \
  --set 'sensors.preset="consumer_gnss"' --set 'estimator.plugin="kf_ins"' \
  --set 'wind.turbulence="moderate"'

rm -rf full killed
case="exchange rounds over the links, central solve (the star's R_i and W_i in flight, clocks out of phase)"
resumed_equals_uninterrupted "$src/experiments/exp2.toml" --no-render \
  --set 'vehicles.model="pointmass"' --set 'attitude={plugin="pointmass_direct"}' \
  --set 'execution={mode="per_agent", coupling="central_solve", predict="input", clock_offset=0.02}' \
  --set 'network={latency=0.004, rounds="over_links"}'

rm -rf full killed
case="Jacobi rounds over lossy, late links with a round timeout (letters in flight, exchanges waiting)"
resumed_equals_uninterrupted "$src/experiments/exp2.toml" --no-render \
  --set 'execution={mode="per_agent", coupling="jacobi", jacobi_rounds=3, predict="input"}' \
  --set 'network={latency=0.01, jitter=0.002, loss=0.1, rounds="over_links", round_timeout=0.02}'

case="another configuration is refused, naming both hashes, and nothing changes"
cp killed/timeseries.csv before.csv
message=$("$bin" run "$src/experiments/exp2.toml" "${short[@]}" --no-render \
  --set 'sensors.preset="consumer_gnss"' --set 'estimator.plugin="kf_ins"' \
  --set 'wind.turbulence="moderate"' --set run.seed=7 \
  --out killed --resume 2>&1)
code=$?
if [ $code != 1 ]; then
  fail "exit $code, not 1"
elif ! grep -q "another configuration (config sha256 [0-9a-f]\{64\}), this run's is [0-9a-f]\{64\}" \
  <<<"$message"; then
  fail "message: $message"
elif ! cmp -s before.csv killed/timeseries.csv; then
  fail "timeseries.csv changed"
else
  ok
fi

case="--resume without a checkpoint"
"$bin" run "$src/experiments/exp2.toml" "${short[@]}" --no-render --out full --resume 2>err.txt
code=$?
if [ $code != 1 ] || ! grep -q "no checkpoint to resume from" err.txt; then
  fail "exit $code: $(cat err.txt)"
else
  ok
fi

[ $failures = 0 ] || { echo "$failures failure(s)" >&2; exit 1; }

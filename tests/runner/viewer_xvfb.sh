#!/usr/bin/env bash
# mjformation view under Xvfb: without a display it fails with a clear message (exit 1); with one
# it opens, flies a short Exp 2, saves a screenshot in which the vehicles are found where their
# projection puts them, and closes on the Escape key with exit 0.
# Usage: BUILD_DIR SOURCE_DIR WORK_DIR. Needs Xvfb and xdotool (scripts/setup.sh).
set -euo pipefail
trap 'echo "viewer_xvfb.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
build=$1 src=$2 work=$3
bin="$build/runner/mjformation"
rm -rf "$work" && mkdir -p "$work"
exp=(view "$src/experiments/exp2.toml" --set run.duration=30.0 --set 'run.metric_window=[20.0, 30.0]' --set 'render.snapshots=[]'
     --set render.shadows=false)

# 1. No display: a clear message and exit 1, not a crash.
rc=0
env -u DISPLAY -u WAYLAND_DISPLAY "$bin" "${exp[@]}" > "$work/nodisplay.txt" 2>&1 || rc=$?
[ "$rc" = 1 ] || { echo "exit $rc without a display"; cat "$work/nodisplay.txt"; false; }
grep -q "no display" "$work/nodisplay.txt" || { cat "$work/nodisplay.txt"; false; }

cat > "$work/check_screenshot.py" <<'PY'
import json, math, sys
import matplotlib.image as mpimg
import numpy as np

img = (mpimg.imread(sys.argv[1])[:, :, :3] * 255).astype(int)
meta = json.load(open(sys.argv[1] + ".json"))
h, w = img.shape[:2]
assert (w, h) == (meta["width"], meta["height"]), (w, h)
assert img.std() > 10, f"blank picture (std {img.std():.1f})"

cam = meta["camera"]
az, el = math.radians(cam["azimuth"]), math.radians(cam["elevation"])
f = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
u = np.array([-math.sin(el) * math.cos(az), -math.sin(el) * math.sin(az), math.cos(el)])
r = np.cross(f, u)
eye = np.array(cam["lookat"]) - cam["distance"] * f
t = math.tan(math.radians(meta["fovy_deg"]) / 2)

def pixel(p):  # MuJoCo's free camera, perspective with vertical field of view fovy
    v = np.array(p) - eye
    x, y, z = v @ r, v @ u, v @ f
    return (x / (z * t * w / h) + 1) / 2 * w, (1 - y / (z * t)) / 2 * h

def vehicle_like(px, py, half=4):
    # Marker discs (saturated palette colours) and the dark frames; the ground is grey-green.
    x0, y0 = int(round(px)), int(round(py))
    patch = img[max(0, y0 - half):y0 + half + 1, max(0, x0 - half):x0 + half + 1]
    sat = patch.max(axis=2) - patch.min(axis=2)
    return int(((sat > 70) | (patch.max(axis=2) < 35)).sum())

found = []
for i, p in enumerate(meta["positions"]):
    px, py = pixel(p)
    assert 0 <= px < w and 0 <= py < h, f"vehicle {i} projects outside the picture ({px}, {py})"
    found.append(vehicle_like(px, py))
print("vehicle pixels near each projected vehicle:", found)
assert all(n >= 8 for n in found), found
# Control: the same test 3 m beside each vehicle (perpendicular to the view) mostly finds ground.
control = [vehicle_like(*pixel(np.array(p) + 3 * r)) for p in meta["positions"]]
print("control, 3 m to the side:", control)
assert sum(n >= 8 for n in control) <= 2, control
print(f"screenshot t = {meta['time']:.2f} s: {len(found)} vehicles found where projected")
# The legend, top right: a flat swatch per vehicle (leader, follower 1..N), each its own colour.
corner = img[: h // 2, w - 320:].reshape(-1, 3)
flat = corner[(corner.max(axis=1) - corner.min(axis=1)) > 100]
colours, counts = np.unique(flat, axis=0, return_counts=True)
swatches = colours[counts >= 150]
print("legend swatches:", len(swatches), swatches.tolist())
assert len(swatches) >= len(meta["positions"]), f"legend: {len(swatches)} swatches"
PY

# 2. With a display (a private Xvfb; -displayfd picks a free number).
exec 5> "$work/display.txt"
Xvfb -displayfd 5 -screen 0 1024x768x24 -nolisten tcp > "$work/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null || true' EXIT
for _ in $(seq 50); do [ -s "$work/display.txt" ] && break; sleep 0.1; done
export DISPLAY=":$(head -1 "$work/display.txt")"
shot="$work/view.png"
"$bin" "${exp[@]}" --screenshot "$shot" --screenshot-at 2.0 --keep-open > "$work/view.log" 2>&1 &
viewer=$!
for _ in $(seq 300); do [ -s "$shot.json" ] && break; sleep 0.2; done
[ -s "$shot.json" ] || { cat "$work/view.log"; false; }
# The key goes to the window through the X server, as a user's would.
win=$(xdotool search --sync --name "mjformation-view: exp2" | head -1)
# The title the README gives: "mjformation-view: NAME".
title=$(xdotool getwindowname "$win")
[ "$title" = "mjformation-view: exp2" ] || { echo "window title '$title'"; false; }
# Keys act: pause, two single steps of 1 ms, double speed, reset to t = 0, then quit.
for key in space Right Right plus BackSpace; do
  xdotool key --window "$win" $key
  sleep 1
done
xdotool key --window "$win" Escape
for _ in $(seq 100); do kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
if kill -0 $viewer 2>/dev/null; then
  kill $viewer
  echo "the viewer did not close on Escape"
  false
fi
wait $viewer || { echo "viewer exit $?"; cat "$work/view.log"; false; }

/usr/bin/python3 - "$work/view.log" <<'PY'
import re, sys
lines = [l for l in open(sys.argv[1]) if re.match(r"\w[\w ]*: t = ", l)]
got = {l.split(":")[0]: float(re.search(r"t = ([0-9.]+)", l).group(1)) for l in lines}
print("".join(lines), end="")
kinds = [l.split(":")[0] for l in lines]
assert kinds == ["paused", "step", "step", "speed", "reset"], kinds
steps = [float(re.search(r"t = ([0-9.]+)", l).group(1)) for l in lines[:3]]
assert abs(steps[1] - steps[0] - 0.001) < 1e-6 and abs(steps[2] - steps[1] - 0.001) < 1e-6, steps
assert "speed x2" in lines[3], lines[3]
assert got["reset"] == 0.0, got
PY
# The picture: not blank, and vehicle pixels where the camera projects the vehicles.
/usr/bin/python3 "$work/check_screenshot.py" "$shot"

# 3. `mjformation replay RUN_DIR` shows a recorded run in the same window, closes the same way.
"$bin" run "$src/experiments/exp2.toml" --set run.duration=4.0 --set 'run.metric_window=[2.0, 4.0]' --set 'render.snapshots=[]' \
  --set render.shadows=false --out "$work/run" --no-render -q
# `mjformation replay RUN_DIR` opens the window (mjformation-view --replay) and closes on Escape.
"$bin" replay "$work/run" > "$work/replay_cli.log" 2>&1 &
replay=$!
win=$(xdotool search --sync --name "mjformation-view: exp2" | head -1)
xdotool key --window "$win" Escape
for _ in $(seq 100); do kill -0 $replay 2>/dev/null || break; sleep 0.1; done
if kill -0 $replay 2>/dev/null; then kill $replay; echo "replay did not close on Escape"; false; fi
wait $replay || { echo "replay exit $?"; cat "$work/replay_cli.log"; false; }
# The replayed picture, through mjformation-view's screenshot option.
rshot="$work/replay.png"
"$build/runner/mjformation-view" --replay "$work/run" --screenshot "$rshot" --screenshot-at 2.0 \
  > "$work/replay.log" 2>&1 &
replay=$!
for _ in $(seq 300); do [ -s "$rshot.json" ] && break; sleep 0.2; done
[ -s "$rshot.json" ] || { cat "$work/replay.log"; false; }
# Without --keep-open the window closes by itself once the screenshot is saved.
for _ in $(seq 100); do kill -0 $replay 2>/dev/null || break; sleep 0.1; done
if kill -0 $replay 2>/dev/null; then kill $replay; echo "the window stayed open after --screenshot"; false; fi
wait $replay
# `mjformation view --help` is mjformation-view's own help: every option is listed.
"$bin" view --help > "$work/view_help.txt"
for option in --screenshot --screenshot-at --keep-open --speed --replay --size --set --plugin-path; do
  grep -q -- "$option" "$work/view_help.txt" || { cat "$work/view_help.txt"; false; }
done
/usr/bin/python3 "$work/check_screenshot.py" "$rshot"
echo "viewer under Xvfb: OK"

#!/usr/bin/env bash
# The README's examples, run as a user would paste them: every
# `build/runner/mjformation ...` and `PYTHONPATH=... python3 ...` command of its bash blocks, and
# the inline `build/runner/mjformation run ...` ones, from a folder that looks like a checkout.
# Shortened only where a user's patience is not the point: runs and sweeps end at 21 s (the
# replay's --snapshots 10,20 still fall inside) without rendering, at 2 video frames per second
# for the replay; bench measures 0.2 s. Not run: `view` (a window: tests/runner/viewer_xvfb.sh),
# MuJoCo's viewer (a window), `cmake --install` and what follows it
# (tests/runner/cmake_package.sh), scripts/*.sh (the studies: minutes to hours), mpirun/srun and
# lines with "..." (placeholders).
# Usage: readme_examples.sh BUILD_DIR WORK_DIR
set -uo pipefail
build=$(cd "$1" && pwd) work=$2
source=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
for d in experiments examples analysis mjcf; do ln -s "$source/$d" "$d"; done
# The project's environment (`mujoco` beside our module), as a checkout has it after setup.sh.
[ -d "$source/.venv" ] && ln -s "$source/.venv" .venv
ln -s "$build" build
short_run=(--no-render --set run.duration=21 --set 'run.metric_window=[10.0,21.0]')
# The commands, one per line, continuation lines joined and trailing comments dropped.
/usr/bin/python3 - "$source/README.md" > commands.txt <<'PY'
import re, shlex, sys
text = open(sys.argv[1]).read()
commands = []
for block in re.findall(r"```bash\n(.*?)```", text, re.S):
    joined = re.sub(r"\\\n\s*", " ", block)
    for line in joined.splitlines():
        line = line.strip()
        try:
            words = shlex.split(line, comments=True)
        except ValueError:
            continue
        if not words:
            continue
        # Drop a trailing comment by re-quoting what shlex kept.
        line = " ".join(shlex.quote(w) if i else w for i, w in enumerate(words))
        if words[0] == "cmake" and "--install" in words:
            break  # the rest of this block needs an install
        commands.append(line)
for inline in re.findall(r"`(build/runner/mjformation run [^`]+)`", text):
    commands.append(inline)
for line in commands:
    if "..." in line or line.startswith(("mpirun", "srun", "bash ", "#")):
        continue
    if line.startswith("build/runner/mjformation view") or "mujoco.viewer" in line:
        continue  # a window
    if line.startswith("build/runner/mjformation replay") and not ("--video" in line or "--snapshots" in line):
        continue  # a window
    if line.startswith(("build/runner/mjformation", "PYTHONPATH=")):
        print(line)
PY
failures=0 passed=0
while IFS= read -r line; do
  eval "words=($line)"
  extra=()
  case "${words[1]:-}" in
    run) extra=("${short_run[@]}" --set render.video_fps=2) ;;
    sweep) extra=("${short_run[@]}") ;;
    bench) extra=(--duration 0.2) ;;
  esac
  [[ $line == PYTHONPATH=* ]] && extra=()
  if [[ $line == PYTHONPATH=build/python* ]] && [ ! -d build/python/mjformation ]; then
    echo "skip $line (no Python module in this build: the sanitizer build has none)"
    continue
  fi
  eval "$line"' "${extra[@]}"' >out.txt 2>err.txt
  code=$?
  if [ $code = 0 ]; then
    echo "ok   $line"
    passed=$((passed + 1))
  else
    echo "FAIL (exit $code) $line: $(tail -c 600 err.txt)" >&2
    failures=$((failures + 1))
  fi
done < commands.txt
# After either README command every plugin family is built: `plugins` lists one plugin (at least)
# from each family's library (scripts/reproduce.sh builds mjf_product; dev/product_target.py).
build/runner/mjformation plugins >plugins.txt 2>&1
for family in "$source"/plugins/*/; do
  family=$(basename "$family")
  if grep -q "library: .*/libmjf_${family}\.so$" plugins.txt; then
    echo "ok   mjformation plugins lists the $family family"
    passed=$((passed + 1))
  else
    echo "FAIL mjformation plugins lists no plugin of libmjf_${family}.so: build the mjf_product target" >&2
    failures=$((failures + 1))
  fi
done
[ $passed -ge 15 ] || { echo "FAIL: only $passed README commands found" >&2; failures=$((failures + 1)); }
echo "readme_examples: $passed passed, $failures failed"
[ $failures = 0 ]

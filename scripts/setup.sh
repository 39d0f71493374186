#!/usr/bin/env bash
# Installs what mjformation needs, only what is missing. Idempotent.
#  - Debian 12 packages, with apt-get;
#  - the pinned PyPI packages of requirements.txt (MuJoCo's official release among them) into the
#    project-local environment .venv (created with Debian's python3, so the analysis keeps
#    Debian's matplotlib and pandas through its system site-packages).
set -euo pipefail
PACKAGES=(
  build-essential cmake pkg-config git
  libeigen3-dev libosmesa6-dev
  libtomlplusplus-dev libtinyxml2-dev libcli11-dev nlohmann-json3-dev libfmt-dev libpng-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev ffmpeg
  libglfw3-dev xvfb xdotool
  libopenmpi-dev openmpi-bin
  python3 python3-numpy python3-matplotlib python3-pytest
  python3-dev pybind11-dev python3-pybind11 python3-pandas python3-venv
  clang clang-format libclang-rt-14-dev
)
missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all packages present"
fi

# The pinned PyPI packages, exactly (--no-deps: requirements.txt lists the whole closure). A stamp
# holding requirements.txt's SHA-256 marks an environment that is complete; an interrupted
# install leaves no stamp and is redone.
root=$(cd "$(dirname "$0")/.." && pwd)
env_dir=${MJF_PYTHON_ENV:-$root/.venv}
want=$(sha256sum "$root/requirements.txt" | cut -d' ' -f1)
if [ "$(cat "$env_dir/.mjformation-requirements" 2>/dev/null)" != "$want" ]; then
  echo "setup: installing requirements.txt into $env_dir"
  rm -f "$env_dir/.mjformation-requirements"
  [ -x "$env_dir/bin/python" ] || /usr/bin/python3 -m venv --system-site-packages "$env_dir"
  "$env_dir/bin/python" -m pip install -q --disable-pip-version-check --no-deps \
    -r "$root/requirements.txt"
  echo "$want" > "$env_dir/.mjformation-requirements"
else
  echo "setup: $env_dir matches requirements.txt"
fi

#!/usr/bin/env bash
# Installs the Debian 12 packages mjformation needs, only those missing. Idempotent.
set -euo pipefail
PACKAGES=(
  build-essential cmake pkg-config git
  libmujoco-dev libmujoco-samples libqhull-dev libeigen3-dev libosmesa6-dev
  libtomlplusplus-dev libtinyxml2-dev libcli11-dev nlohmann-json3-dev libfmt-dev libpng-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev ffmpeg
  libglfw3-dev xvfb xdotool
  libopenmpi-dev openmpi-bin
  python3 python3-numpy python3-matplotlib python3-pytest
  python3-dev pybind11-dev python3-pybind11 python3-pandas
  clang libclang-rt-14-dev
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

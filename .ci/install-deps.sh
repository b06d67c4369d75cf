#!/usr/bin/env bash
# Installs every Debian package kasha needs to build, test and benchmark. Idempotent. clang 14 (with
# libFuzzer and the sanitizer runtimes in libclang-rt-14-dev) builds .ci/sanitize-build.sh's tree.
set -euo pipefail
PACKAGES=(
  build-essential cmake ccache pkg-config
  libembree-dev libopenexr-dev libimath-dev libflann-dev liblz4-dev libglm-dev libtbb-dev
  nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libtinyobjloader-dev libcli11-dev libpng-dev libjpeg62-turbo-dev libstb-dev libpugixml-dev libassimp-dev zlib1g-dev
  libopenmpi-dev openmpi-bin
  python3-numpy python3-matplotlib
  python3-dev pybind11-dev python3-pybind11 python3-pytest
  clang-14 libclang-rt-14-dev
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"

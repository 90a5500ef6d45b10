#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian packages smb needs to build, test, run and plot. Does nothing when they
# are all present already, so it is cheap to call from every other script.
set -euo pipefail

packages=(
  cmake
  g++
  make
  libgtest-dev
  libgmock-dev
  libbenchmark-dev
  libcli11-dev
  nlohmann-json3-dev
  libfmt-dev
  python3-numpy
  python3-matplotlib
  # the Python module (python/, docs/python.md) and its tests
  pybind11-dev
  python3-dev
  python3-pytest
  # the code's format (.clang-format; scripts/format.sh --check in scripts/test.sh)
  clang-format
  # libFuzzer targets (fuzz/, scripts/fuzz.sh): clang with its sanitizer and fuzzer runtimes
  clang-14
  libclang-rt-14-dev
  # Bullet: smb::bullet (src/bullet/, examples/bullet/) and a peer of the side-by-side benchmark;
  # Box2D and CGAL: peers of that benchmark (bench/peers/). Optional: the build skips any missing
  libbullet-dev
  libbox2d-dev
  libcgal-dev
  # distributed detection (smb::mpi, tests/mpi/): OpenMPI and its mpirun
  libopenmpi-dev
  openmpi-bin
)

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$package")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update
"${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${packages[@]}"

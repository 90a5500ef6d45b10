#!/bin/sh
# SPDX-License-Identifier: MIT
# Builds smb_compare in release mode and runs the side-by-side comparison, then the plots.
#   scripts/bench-compare.sh [quick|full] [machine-name] [build-dir]
# Results: bench/results/<machine-name>/<mode>.csv, .jsonl, -tables.md and PNG plots.
# The peers are optional (Debian: libbullet-dev libbox2d-dev libcgal-dev); those missing are
# left out of the build and of the tables.
set -eu
mode="${1:-quick}"
machine="${2:-cpp-2core}"
build_dir="${3:-build-bench}"
root="$(cd "$(dirname "$0")/.." && pwd)"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DSMB_BUILD_BENCHMARKS=ON \
      -DSMB_BUILD_TESTS=OFF -DSMB_BUILD_TOOLS=OFF >/dev/null
cmake --build "$build_dir" --target smb_compare -j "${SMB_BUILD_JOBS:-2}"
/usr/bin/python3 "$root/scripts/bench-compare.py" --build-dir "$build_dir" --mode "$mode" --machine "$machine"
/usr/bin/python3 "$root/scripts/plot-compare.py" "$root/bench/results/$machine/$mode.csv"

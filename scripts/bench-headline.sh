#!/bin/sh
# SPDX-License-Identifier: MIT
# Builds smb_compare in release mode and runs the headline comparison (scripts/bench-headline.py):
# the paper's workload at 1M boxes in 3D and 100k in 2D, and the other scene families at 300k in
# 3D and 100k in 2D, smb against the uniform grid (one and two threads), the Verlet-skin grid,
# Bullet's DBVT and Box2D's tree, and at 3D 1M the grid and the Detector over arrays renumbered in
# their own orders; 40 steps, the build step and the steady state apart.
#   scripts/bench-headline.sh [name] [build-dir] [more options of bench-headline.py]
# Results: bench/results/cpp-2core/<name>.csv, .jsonl and .md. About 25 minutes on 2 idle cores.
set -eu
name="${1:-headline}"
build_dir="${2:-build-bench}"
[ $# -gt 0 ] && shift
[ $# -gt 0 ] && shift
root="$(cd "$(dirname "$0")/.." && pwd)"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DSMB_BUILD_BENCHMARKS=ON \
      -DSMB_BUILD_TESTS=OFF -DSMB_BUILD_TOOLS=OFF >/dev/null
cmake --build "$build_dir" --target smb_compare -j "${SMB_BUILD_JOBS:-2}"
exec /usr/bin/python3 "$root/scripts/bench-headline.py" --build-dir "$build_dir" --name "$name" "$@"

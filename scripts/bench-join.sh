#!/bin/sh
# SPDX-License-Identifier: MIT
# Builds smb_join_compare in release mode and runs the two-set comparison: smb's one-shot
# find_overlapping_pairs(first, second) beside CGAL's box_intersection_d over two sequences and
# beside one detection of the union, on two placements of the paper's workload and on particles
# against a mesh-like height field, 3D and 2D. Prints a markdown table (bench/results/cpp-2core/join.md),
# with the load average before and after, since the times are wall times.
#   scripts/bench-join.sh [build-dir] [rounds]
# About 3 minutes with 5 rounds (on 2 busy cores).
set -eu
build_dir="${1:-build-bench}"
rounds="${2:-3}"
root="$(cd "$(dirname "$0")/.." && pwd)"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DSMB_BUILD_BENCHMARKS=ON \
      -DSMB_BUILD_TESTS=OFF -DSMB_BUILD_TOOLS=OFF >/dev/null
cmake --build "$build_dir" --target smb_join_compare -j "${SMB_BUILD_JOBS:-2}" >/dev/null
bin="$build_dir/bench/smb_join_compare"
echo "uptime before: $(uptime)"
echo
"$bin" --header --scene paper --dim 3 --first 100000 --second 100000 --rounds "$rounds"
"$bin" --scene paper --dim 3 --first 1000000 --second 1000000 --rounds "$rounds"
"$bin" --scene mesh --dim 3 --first 100000 --second 10000 --rounds "$rounds"
"$bin" --scene mesh --dim 3 --first 1000000 --second 100000 --rounds "$rounds"
"$bin" --scene mesh --dim 3 --first 1000000 --second 1000 --rounds "$rounds"
"$bin" --scene paper --dim 2 --first 1000000 --second 1000000 --rounds "$rounds"
"$bin" --scene mesh --dim 2 --first 1000000 --second 10000 --rounds "$rounds"
echo
echo "uptime after: $(uptime)"

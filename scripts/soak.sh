#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Long runs of docs/robustness.md, with smb_soak from a Release build (build-hard/, or
# SMB_HARD_BUILD_DIR):
#   scripts/soak.sh soak  [steps]   100 000 boxes in 3D, 20% removed and as many inserted every
#                                   step (default 10 000 steps), exact against the grid every
#                                   100 steps, memory sampled every 100 steps
#   scripts/soak.sh scale [boxes]   one world of 10 000 000 boxes in 3D (or [boxes]), 3 steps
#                                   with 20% churn, bytes per box and time per step, no check
# The CSV of samples goes to standard output and, with its summary, to
# $SMB_SOAK_OUT (default /tmp/smb-<mode>.csv); peak memory is printed by /usr/bin/time -v.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"

mode=${1:-soak}
build_dir=${SMB_HARD_BUILD_DIR:-build-hard}
jobs=${SMB_JOBS:-2}
out=${SMB_SOAK_OUT:-/tmp/smb-$mode.csv}

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DSMB_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build_dir" --parallel "$jobs" --target smb_soak >/dev/null
soak="$build_dir/tests/smb_soak"

case "$mode" in
  soak)
    steps=${2:-10000}
    /usr/bin/time -v "$soak" --dim 3 --boxes 100000 --steps "$steps" --churn 0.2 \
      --sample-every 100 --check-every 100 | tee "$out"
    ;;
  scale)
    boxes=${2:-10000000}
    /usr/bin/time -v "$soak" --dim 3 --boxes "$boxes" --steps 3 --churn 0.2 \
      --sample-every 1 --check-every 0 | tee "$out"
    ;;
  *)
    echo "usage: scripts/soak.sh soak [steps] | scale [boxes]" >&2
    exit 2
    ;;
esac

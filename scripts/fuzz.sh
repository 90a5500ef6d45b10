#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs one libFuzzer target for a given time:
#   scripts/fuzz.sh <scene_csv|world_ops|detector_ops> <seconds>
# Configures and builds the fuzz build (clang++, address + undefined-behaviour sanitizers,
# SMB_BUILD_FUZZERS) in build-fuzz/ (SMB_FUZZ_BUILD_DIR overrides), then fuzzes starting from
# the committed seeds (fuzz/corpus/<target>) and the regressions (fuzz/regressions/<target>).
# New interesting inputs go to <build>/fuzz/work/<target>, never into the source tree. A crash
# leaves its input in <build>/fuzz/artifacts/<target>/ and the script exits non-zero; copy that
# file into fuzz/regressions/<target>/ once it is fixed, so the test suite replays it forever.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"

if [[ $# -ne 2 ]]; then
  echo "usage: scripts/fuzz.sh <scene_csv|world_ops|detector_ops> <seconds>" >&2
  exit 2
fi
target=$1
seconds=$2
case "$target" in
  scene_csv) max_len=4096 ;;
  world_ops) max_len=512 ;;
  detector_ops) max_len=512 ;;
  *) echo "fuzz.sh: unknown target '$target' (scene_csv, world_ops or detector_ops)" >&2; exit 2 ;;
esac

build_dir=${SMB_FUZZ_BUILD_DIR:-build-fuzz}
compiler=${SMB_FUZZ_CXX:-clang++}
jobs=${SMB_JOBS:-2}

if ! command -v "$compiler" >/dev/null; then
  echo "fuzz.sh: $compiler not found (Debian: clang-14 and libclang-rt-14-dev)" >&2
  exit 2
fi

cmake -S . -B "$build_dir" -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DSMB_SANITIZE=ON -DSMB_BUILD_FUZZERS=ON -DSMB_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build_dir" --parallel "$jobs" --target "fuzz_$target"

work_dir="$build_dir/fuzz/work/$target"
artifact_dir="$build_dir/fuzz/artifacts/$target"
mkdir -p "$work_dir" "$artifact_dir"
seed_dirs=(fuzz/corpus/"$target")
if [[ -d fuzz/regressions/$target ]] && [[ -n $(ls -A "fuzz/regressions/$target") ]]; then
  seed_dirs+=(fuzz/regressions/"$target")
fi
dictionary=()
if [[ -f fuzz/$target.dict ]]; then
  dictionary=(-dict="fuzz/$target.dict")
fi

# SMB_FUZZ_RUNS=N makes the run reproducible: exactly N inputs from seed 1 (the time is then
# only a cap). CI uses it, so that what passed here passes there.
# The corpus a run grows is emptied first, so that a run here starts where a clean clone does.
repeatable=()
if [[ -n ${SMB_FUZZ_RUNS:-} ]]; then
  repeatable=(-runs="$SMB_FUZZ_RUNS" -seed=1)
  rm -rf "$work_dir"
  mkdir -p "$work_dir"
fi

echo "== fuzz_$target for ${seconds}s${SMB_FUZZ_RUNS:+ or $SMB_FUZZ_RUNS runs} =="
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
  "$build_dir/fuzz/fuzz_$target" -max_total_time="$seconds" -max_len="$max_len" \
  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$artifact_dir/" "${dictionary[@]}" "${repeatable[@]}" "$work_dir" "${seed_dirs[@]}"

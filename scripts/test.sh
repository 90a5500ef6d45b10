#!/usr/bin/env bash
# The whole check, as CI runs it:
#   1. Release build with warnings as errors and the SMB invariant checks on (build-ci/),
#      every test;
#   2. address + undefined-behaviour sanitizer build (build-ci-asan/), every test but the
#      consumer proof, which builds its own uninstrumented copies and was proven in step 1.
# Exits non-zero if any build or test fails.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"

jobs=${SMB_JOBS:-2}

bash scripts/install-deps.sh

echo "== Release build (warnings as errors, SMB_VALIDATE) =="
cmake -S . -B build-ci -DCMAKE_BUILD_TYPE=Release \
  -DSMB_WARNINGS_AS_ERRORS=ON -DSMB_VALIDATE=ON
cmake --build build-ci --parallel "$jobs"
ctest --test-dir build-ci --output-on-failure -j"$jobs"

echo "== Sanitizer build (ASan + UBSan) =="
cmake -S . -B build-ci-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSMB_SANITIZE=ON -DSMB_WARNINGS_AS_ERRORS=ON -DSMB_VALIDATE=ON -DSMB_BUILD_BENCHMARKS=OFF
cmake --build build-ci-asan --parallel "$jobs"
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
  ctest --test-dir build-ci-asan --output-on-failure -j"$jobs" -LE consumer

echo "== all checks passed =="

#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The whole check, as CI runs it:
#   0. every C++ source formatted as .clang-format says (scripts/format.sh --check);
#   1. Release build with warnings as errors and the SMB invariant checks on (build-ci/),
#      every test;
#   2. address + undefined-behaviour sanitizer build (build-ci-asan/), every test but the
#      consumer proof, which builds its own uninstrumented copies and was proven in step 1, and
#      the World tests repeated on the paper's pipeline (label paper_pipeline), which step 1
#      runs; the paper's pipeline stays under the sanitizers through its own tests;
#   3. a minute of libFuzzer on each fuzz target (build-ci-fuzz/), where clang has libFuzzer.
# Exits non-zero if any build or test fails. SMB_CI_BUILD_DIR and SMB_CI_ASAN_BUILD_DIR pick
# other build folders, SMB_JOBS the parallelism (default 2).
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"

jobs=${SMB_JOBS:-2}
release_dir=${SMB_CI_BUILD_DIR:-build-ci}
asan_dir=${SMB_CI_ASAN_BUILD_DIR:-build-ci-asan}

bash scripts/install-deps.sh

echo "== Format (clang-format) =="
bash scripts/format.sh --check

echo "== Release build (warnings as errors, SMB_VALIDATE) =="
cmake -S . -B "$release_dir" -DCMAKE_BUILD_TYPE=Release \
  -DSMB_WARNINGS_AS_ERRORS=ON -DSMB_VALIDATE=ON
cmake --build "$release_dir" --parallel "$jobs"
ctest --test-dir "$release_dir" --output-on-failure -j"$jobs"

echo "== Sanitizer build (ASan + UBSan) =="
# -O1, as AddressSanitizer's documentation advises: it compiles about 30% faster than -O2 (the
# build is most of this stage) and the tests stay fast enough. Line tables only (-g1): the
# sanitizers' reports name file and line.
cmake -S . -B "$asan_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DSMB_SANITIZE=ON -DSMB_WARNINGS_AS_ERRORS=ON -DSMB_VALIDATE=ON -DSMB_BUILD_BENCHMARKS=OFF \
  -DSMB_BUILD_PYTHON=OFF
# No Python module here: an uninstrumented interpreter cannot load an ASan module without
# LD_PRELOAD of the runtime. The C++ beneath it runs under ASan in the C++ tests; the module and
# its pytest run in the Release build above.
cmake --build "$asan_dir" --parallel "$jobs"
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
  ctest --test-dir "$asan_dir" --output-on-failure -j"$jobs" -LE 'consumer|paper_pipeline'

echo "== Short fuzzing (libFuzzer, ASan + UBSan) =="
# 40 000 inputs from seed 1 per target (SMB_FUZZ_RUNS), stopped after 60 s (SMB_FUZZ_SECONDS)
# to bound CI's time, so the run starts the same on every machine; skipped where clang cannot link
# libFuzzer.
fuzz_probe='extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }'
if command -v clang++ >/dev/null &&
   echo "$fuzz_probe" | clang++ -fsanitize=fuzzer -x c++ - -o /dev/null 2>/dev/null; then
  for target in scene_csv world_ops detector_ops; do
    SMB_FUZZ_BUILD_DIR=${SMB_CI_FUZZ_BUILD_DIR:-build-ci-fuzz} \
    SMB_FUZZ_RUNS=${SMB_FUZZ_RUNS:-40000} \
      bash scripts/fuzz.sh "$target" "${SMB_FUZZ_SECONDS:-60}"
  done
else
  echo "skipped: clang++ with libFuzzer not available"
fi

echo "== all checks passed =="

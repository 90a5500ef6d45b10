#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds smb (Release, into build/) and runs `smb run` with the given arguments:
#   bash scripts/run.sh                 the default scene
#   bash scripts/run.sh --help          every option
# SMB_BUILD_DIR picks another build folder.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"
build_dir=${SMB_BUILD_DIR:-build}

bash scripts/install-deps.sh
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release --log-level=WARNING >&2
cmake --build "$build_dir" --parallel 2 --target smb_cli >&2
exec "$build_dir/tools/smb/smb" run "$@"

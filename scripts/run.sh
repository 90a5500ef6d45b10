#!/usr/bin/env bash
# Builds smb (Release, into build/) and runs `smb run` with the given arguments:
#   bash scripts/run.sh                 the default scene
#   bash scripts/run.sh --help          every option
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"

bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release --log-level=WARNING >&2
cmake --build build --parallel 2 --target smb_cli >&2
exec build/tools/smb/smb run "$@"

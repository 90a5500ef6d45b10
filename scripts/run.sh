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

smb="$build_dir/tools/smb/smb"

# Only --help (or -h) with the tool built: print it at once, without checking the packages or
# building again.
only_help=$(( $# > 0 ))
for argument in "$@"; do
  [[ $argument == --help || $argument == -h ]] || only_help=0
done
if (( only_help )) && [[ -x $smb ]]; then
  exec "$smb" run "$@"
fi

bash scripts/install-deps.sh
# CMake's own progress ("Configuring done", ...) goes to standard output: dropped; its warnings
# and errors go to standard error.
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release --log-level=WARNING >/dev/null
cmake --build "$build_dir" --parallel 2 --target smb_cli >&2
exec "$smb" run "$@"

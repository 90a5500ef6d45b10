#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Formats every C++ source of the project with .clang-format (Debian's clang-format 14).
#   bash scripts/format.sh          rewrites the files in place
#   bash scripts/format.sh --check  changes nothing; exits 1 and names the files that differ
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

formatter=${CLANG_FORMAT:-}
if [[ -z "$formatter" ]]; then
  for candidate in clang-format-14 clang-format; do
    if command -v "$candidate" >/dev/null; then formatter=$candidate; break; fi
  done
fi
if [[ -z "$formatter" ]]; then
  echo "format.sh: clang-format not found (apt-get install clang-format)" >&2
  exit 2
fi

mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' ':!:tests/data/**' ':!:fuzz/corpus/**' ':!:fuzz/regressions/**')
if [[ "${1:-}" == "--check" ]]; then
  differ=()
  for file in "${files[@]}"; do
    if ! "$formatter" --style=file "$file" | cmp -s - "$file"; then differ+=("$file"); fi
  done
  if [[ ${#differ[@]} -gt 0 ]]; then
    printf 'format.sh: not formatted (run bash scripts/format.sh):\n'
    printf '  %s\n' "${differ[@]}"
    exit 1
  fi
  echo "format.sh: ${#files[@]} files formatted"
else
  "$formatter" --style=file -i "${files[@]}"
fi

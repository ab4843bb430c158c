#!/usr/bin/env bash
# The house format (.clang-format) on every C++ file of src/, tests/ and perf/.
#   scripts/format.sh           reformat in place
#   scripts/format.sh --check   list the files that differ from the format; exit 1 if any
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
if ! command -v clang-format >/dev/null 2>&1; then
  echo "[format] installing clang-format" >&2
  apt-get update -qq >/dev/null && apt-get install -y -qq clang-format >/dev/null
fi
mapfile -t files < <(git ls-files 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp' 'perf/*.cpp' 'perf/*.hpp')
if [[ "${1:-}" == "--check" ]]; then
  bad=0
  for f in "${files[@]}"; do
    if ! clang-format --style=file "$f" | cmp -s - "$f"; then
      echo "[format] not formatted: $f (run scripts/format.sh)"
      bad=1
    fi
  done
  [[ $bad == 0 ]] && echo "[format] ${#files[@]} files formatted"
  exit $bad
fi
clang-format -i --style=file "${files[@]}"

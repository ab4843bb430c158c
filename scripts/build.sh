#!/usr/bin/env bash
# Set-up if needed, then configure and build scpdyn into build/ (executable: build/bin/scpdyn).
# Environment: SCPDYN_BUILD_DIR (default build), SCPDYN_BUILD_TYPE (default Release),
# SCPDYN_JOBS (default: number of cores).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
KOKKOS_PREFIX="$(bash "$ROOT/scripts/setup.sh" | tail -n 1)"
BUILD_DIR="${SCPDYN_BUILD_DIR:-$ROOT/build}"
JOBS="${SCPDYN_JOBS:-$(nproc)}"
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="${SCPDYN_BUILD_TYPE:-Release}" \
  -DCMAKE_PREFIX_PATH="$KOKKOS_PREFIX" "${launcher[@]}" "$@" >&2 \
  || { echo "[build] CMake configure failed (see above)" >&2; exit 1; }
cmake --build "$BUILD_DIR" -j"$JOBS" >&2 || { echo "[build] compilation failed (see above)" >&2; exit 1; }
echo "$BUILD_DIR"

#!/usr/bin/env bash
# The whole test suite: set-up and build if needed, then every ctest test.
#   scripts/test.sh [ctest options]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="$(bash "$ROOT/scripts/build.sh" | tail -n 1)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$BUILD_DIR"
ctest --output-on-failure -j"${SCPDYN_TEST_JOBS:-2}" "$@"

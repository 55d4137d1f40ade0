#!/usr/bin/env bash
# Builds (if needed) and runs every test. Tests that need ../shared/data skip
# with a message when it is absent.
#   scripts/test.sh                     # the tests CI runs
#   scripts/test.sh -R Trajectory       # extra arguments go to ctest
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${DLSLAM_BUILD_DIR:-build}"
[ -f "$BUILD_DIR/CMakeCache.txt" ] || scripts/setup.sh
cmake --build "$BUILD_DIR" --parallel "$(nproc)"
ctest --test-dir "$BUILD_DIR" --output-on-failure --parallel "$(nproc)" "$@"

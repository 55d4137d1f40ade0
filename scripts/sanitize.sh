#!/usr/bin/env bash
# Builds and tests under a sanitizer in its own build folder.
#   scripts/sanitize.sh address   # ASan + UBSan -> build-asan/
#   scripts/sanitize.sh thread    # TSan         -> build-tsan/
set -euo pipefail
cd "$(dirname "$0")/.."
kind="${1:?usage: scripts/sanitize.sh address|thread [ctest args]}"
shift
case "$kind" in
  address) dir=build-asan ;;
  thread) dir=build-tsan ;;
  *) echo "unknown sanitizer '$kind' (address or thread)" >&2; exit 2 ;;
esac
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDLSLAM_SANITIZE="$kind" \
  -DDLSLAM_BUILD_BENCHMARKS=OFF
cmake --build "$dir" --parallel "$(nproc)"
# Third-party reports we cannot fix are suppressed, each with its reason, in
# scripts/sanitizers/*.supp (absolute paths: tests run from their own folders).
supp="$PWD/scripts/sanitizers"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp/tsan.supp"
# A per-test limit, so that a deadlock fails the run instead of hanging it.
# The slowest tests under TSan (SlamPipelineTest: every test process renders
# the 60-frame fixture, then runs SLAM once or twice) take ~55 s on 2 idle
# cores and up to ~280 s on 2 cores shared with other builds.
# The training tests (label python) run no C++ code: skipped here.
# Under TSan, LoopPresetTest.ClosesTheLoopAtTheRightPoseAndReducesDrift (two
# 1125-frame runs with every thread's work done on the calling thread, 55 s in
# a plain build) passes the 10-minute limit; it has no threads to check, and
# its threaded twin ClosesTheLoopWithTheThreads runs (~6.5 min).
skip=()
[[ $kind == thread ]] && skip=(--exclude-regex 'LoopPresetTest\.ClosesTheLoopAtTheRightPoseAndReducesDrift')
ctest --test-dir "$dir" --output-on-failure --parallel "$(nproc)" --timeout 600 --label-exclude python \
  "${skip[@]}" "$@"

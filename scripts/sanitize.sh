#!/usr/bin/env bash
# Builds and tests under a sanitizer in its own build folder.
#   scripts/sanitize.sh address        # ASan + UBSan -> build-asan/, every test
#   scripts/sanitize.sh thread         # TSan         -> build-tsan/, every test
#   scripts/sanitize.sh address --ci   # what CI runs: the readers' unit tests and
#                                      # the fuzz suite (build-asan-ci/, -O1; 8 min build, 40 s run on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
kind="${1:?usage: scripts/sanitize.sh address|thread [--ci] [ctest args]}"
shift
case "$kind" in
  address) dir=build-asan ;;
  thread) dir=build-tsan ;;
  *) echo "unknown sanitizer '$kind' (address or thread)" >&2; exit 2 ;;
esac
# Third-party reports we cannot fix are suppressed, each with its reason, in
# scripts/sanitizers/*.supp (absolute paths: tests run from their own folders).
supp="$PWD/scripts/sanitizers"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp/tsan.supp"

if [[ ${1:-} == --ci ]]; then
  # The unit tests of the modules that read user input (io, eval, place,
  # data, util; semantic for model files: corrupt ONNX, the input-size
  # reader; image for the masks' bit packing) and the fuzz suite over every
  # reader; not the SLAM end to end, which would not fit CI's 2 cores. -O1
  # without debug info compiles fastest.
  dir=build-asan-ci
  targets=(util_test data_test io_test eval_test place_test semantic_test image_test input_fuzz_test)
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 \
    -DDLSLAM_SANITIZE="$kind" -DDLSLAM_BUILD_BENCHMARKS=OFF
  cmake --build "$dir" --parallel "$(nproc)" --target "${targets[@]}"
  export DLSLAM_SOURCE_DIR="$PWD"
  for target in "${targets[@]}"; do
    echo "sanitize: $target"
    "$dir/bin/$target" --gtest_brief=1
  done
  echo "sanitize: ${#targets[@]} test programs clean under $kind"
  exit 0
fi

cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDLSLAM_SANITIZE="$kind" \
  -DDLSLAM_BUILD_BENCHMARKS=OFF
cmake --build "$dir" --parallel "$(nproc)"
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

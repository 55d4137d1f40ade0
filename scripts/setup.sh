#!/usr/bin/env bash
# Installs what DLSLAM needs from Debian 12 packages and builds it (Release)
# into build/. Idempotent and non-interactive: run it again after a pull.
#   scripts/setup.sh                 # packages + build (the SLAM: no PyTorch)
#   scripts/setup.sh --training      # ... + PyTorch & co. for training/ and its tests
#   DLSLAM_BUILD_DIR=b scripts/setup.sh -DDLSLAM_SANITIZE=address   # extra CMake args
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libopencv-dev libjpeg-dev libdeflate-dev libceres-dev libyaml-cpp-dev libcli11-dev
  libspdlog-dev libfmt-dev nlohmann-json3-dev libtbb-dev
  libcurl4-openssl-dev libarchive-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium  # the browser test of dlslam run --html (headless)
)
# training/ (the segmentation network; its one-batch and model tests run with
# /usr/bin/python3 and are skipped without these). PyTorch is the bulk of a
# fresh set-up and the SLAM never uses it, so only on request.
TRAINING_PACKAGES=(python3-torch python3-opencv python3-onnx python3-numpy)

CMAKE_ARGS=()
for arg in "$@"; do
  if [ "$arg" = "--training" ]; then
    PACKAGES+=("${TRAINING_PACKAGES[@]}")
  else
    CMAKE_ARGS+=("$arg")
  fi
done

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

BUILD_DIR="${DLSLAM_BUILD_DIR:-build}"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release ${CMAKE_ARGS[@]+"${CMAKE_ARGS[@]}"}
cmake --build "$BUILD_DIR" --parallel "$(nproc)"
echo "setup: built $BUILD_DIR/bin/dlslam"

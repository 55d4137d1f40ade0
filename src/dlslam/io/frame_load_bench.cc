// Cost of reading one RGB-D frame from disk (the prefetching thread's work
// per frame, FramePrefetcher): the real Bonn crowd frames (640x480 PNGs,
// Xtion) when ../shared/data is there, else a frame written here.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "dlslam/io/image_io.h"
#include "dlslam/io/sequence.h"
#include "dlslam/io/sequence_test_folder.h"
#include "tests/support/test_data.h"

namespace {

namespace fs = std::filesystem;
using dlslam::io::RgbdSequence;

// The Bonn frames, or 10 random-texture frames of 640x480 written to a temp folder.
const RgbdSequence& Frames() {
  static dlslam::io::testing::SequenceFolder written;
  static const RgbdSequence sequence = [] {
    if (const auto shared = dlslam::testing::SharedDataDir()) {
      const fs::path bonn = *shared / "bonn/rgbd_bonn_crowd_280-579";
      if (fs::exists(bonn / "rgb.txt")) return RgbdSequence::Open(bonn);
    }
    written.WriteValidSequence(10, {640, 480});
    return RgbdSequence::Open(written.dir());
  }();
  return sequence;
}

void BM_LoadFrame(benchmark::State& state) {
  const RgbdSequence& frames = Frames();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(frames.LoadFrame(i++ % frames.size()));
  state.SetLabel(frames.folder().filename().string());
}
BENCHMARK(BM_LoadFrame)->Unit(benchmark::kMillisecond);

// The two images of a frame (arg 0: colour, 1: depth) read as LoadFrame
// reads them: bytes, structure check, decode (and depth to metres).
void BM_ReadImage(benchmark::State& state) {
  const RgbdSequence& frames = Frames();
  const bool colour = state.range(0) == 0;
  const dlslam::CameraIntrinsics& camera = frames.camera();
  std::size_t i = 0;
  dlslam::io::ImageSource source;
  for (auto _ : state) {
    const dlslam::io::RgbdFrameInfo& info = frames.frames()[i++ % frames.size()];
    source = {frames.folder() / (colour ? info.rgb.path : info.depth.path), "", 0};
    if (colour) {
      benchmark::DoNotOptimize(dlslam::io::ReadColorImage(source, camera.width, camera.height));
    } else {
      benchmark::DoNotOptimize(dlslam::io::ReadDepthImage(source, camera.depth_factor, camera.width, camera.height));
    }
  }
  state.SetLabel(source.image.extension().string() + (colour ? " colour" : " depth"));
}
BENCHMARK(BM_ReadImage)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);

}  // namespace

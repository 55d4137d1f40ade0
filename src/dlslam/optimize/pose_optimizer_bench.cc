// Motion-only pose optimisation at the size the tracker solves on the real
// Bonn crowd frames: ~340 matches a call (measured: 899 calls, 338 matches
// each on average over the 300 frames, full mode), three calls a frame.
// 1 px noise, a share of wrong matches, the start 2 cm / 0.6 deg off.

#include <benchmark/benchmark.h>

#include "dlslam/optimize/pose_optimizer.h"
#include "tests/support/pose_scene.h"

namespace dlslam {
namespace {

void BM_OptimizePose(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const double outliers = static_cast<double>(state.range(1)) / 100.0;
  const testing::PoseScene s = testing::MakePoseScene(n, outliers, 1.0, 7);
  const SE3d start = testing::PerturbPose(s.cam_from_world, 0.02, 0.01);
  int inliers = 0;
  for (auto _ : state) {
    const PoseOptimizationResult r = OptimizePose(s.camera, start, s.observations);
    inliers = r.num_inliers;
    benchmark::DoNotOptimize(r.cam_from_world);
  }
  state.counters["inliers"] = inliers;
}
// {matches, wrong matches [%]}
BENCHMARK(BM_OptimizePose)->Args({340, 10})->Args({340, 40})->Args({1000, 10})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace dlslam

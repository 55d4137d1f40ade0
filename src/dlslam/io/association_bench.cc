// Cost of associating RGB and depth stamps (and, in eval, estimated and
// ground-truth poses): a 2-minute TUM sequence has ~3600 frames per list and
// ~12000 ground-truth poses at 100 Hz.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "dlslam/io/association.h"

namespace {

// 30 Hz stamps with a few ms of jitter, like Kinect frames.
std::vector<double> Stamps(int n, double rate, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  std::vector<double> t(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    t[static_cast<std::size_t>(i)] = 1341846313.0 + i / rate + jitter(rng);
  return t;
}

void BM_AssociateFrames(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto rgb = Stamps(n, 30.0, 1), depth = Stamps(n, 30.0, 2);
  for (auto _ : state) benchmark::DoNotOptimize(dlslam::io::AssociateTimestamps(rgb, depth));
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_AssociateFrames)->Arg(800)->Arg(3600)->Unit(benchmark::kMicrosecond);

void BM_AssociateGroundTruth(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto frames = Stamps(n, 30.0, 3), gt = Stamps(n * 10 / 3, 100.0, 4);
  for (auto _ : state) benchmark::DoNotOptimize(dlslam::io::AssociateTimestamps(frames, gt));
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_AssociateGroundTruth)->Arg(3600)->Unit(benchmark::kMicrosecond);

}  // namespace

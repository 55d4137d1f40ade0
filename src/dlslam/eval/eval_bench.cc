// ATE and RPE on a 2000-pose estimate against 100 Hz ground truth (a
// ~67 s sequence at 30 Hz): the cost of evaluating one run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "dlslam/eval/associate.h"
#include "dlslam/eval/ate.h"
#include "dlslam/eval/rpe.h"

namespace {

using dlslam::SE3d;
using dlslam::SO3d;
using dlslam::Trajectory;

SE3d Motion(double t) {
  const Eigen::Vector3d p(1.2 * std::sin(0.21 * t), 0.9 * std::sin(0.17 * t + 1.1), 1.4);
  return SE3d(SO3d::Exp(Eigen::Vector3d(0.35 * std::sin(0.31 * t), 0.25, 0.85 * std::sin(0.11 * t))), p);
}

struct Sequence {
  Trajectory gt;
  Trajectory est;
};

const Sequence& TwoThousandPoses() {
  static const Sequence s = [] {
    Sequence seq;
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 0.004);
    std::uniform_real_distribution<double> jitter(-0.002, 0.002);
    const double t0 = 1305031102.175304;
    for (int k = 0; k < 2000 * 10 / 3 + 100; ++k) seq.gt.emplace_back(t0 + 0.01 * k, Motion(0.01 * k));
    for (int k = 0; k < 2000; ++k) {
      const double t = k / 30.0 + jitter(rng);
      SE3d pose = Motion(t);
      pose.translation() += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      seq.est.emplace_back(t0 + t, pose);
    }
    return seq;
  }();
  return s;
}

void BM_Associate(benchmark::State& state) {
  const Sequence& s = TwoThousandPoses();
  for (auto _ : state) benchmark::DoNotOptimize(dlslam::eval::Associate(s.gt, s.est, {}));
}
BENCHMARK(BM_Associate)->Unit(benchmark::kMillisecond);

void BM_Ate(benchmark::State& state) {
  const Sequence& s = TwoThousandPoses();
  for (auto _ : state) benchmark::DoNotOptimize(dlslam::eval::ComputeAte(s.gt, s.est));
}
BENCHMARK(BM_Ate)->Unit(benchmark::kMillisecond);

void BM_Rpe(benchmark::State& state) {
  const Sequence& s = TwoThousandPoses();
  dlslam::eval::RpeOptions options;
  options.delta_unit = static_cast<dlslam::eval::DeltaUnit>(state.range(0));
  options.delta = options.delta_unit == dlslam::eval::DeltaUnit::kFrames ? 30.0 : 1.0;
  for (auto _ : state) benchmark::DoNotOptimize(dlslam::eval::ComputeRpe(s.gt, s.est, options));
}
BENCHMARK(BM_Rpe)
    ->Arg(static_cast<int>(dlslam::eval::DeltaUnit::kSeconds))
    ->Arg(static_cast<int>(dlslam::eval::DeltaUnit::kMeters))
    ->Arg(static_cast<int>(dlslam::eval::DeltaUnit::kFrames))
    ->Unit(benchmark::kMillisecond);

}  // namespace

// Cost of the Lie-group primitives that tracking and bundle adjustment call
// millions of times per sequence.
#include <benchmark/benchmark.h>

#include "dlslam/geometry/se3.h"

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

void BM_SE3Exp(benchmark::State& state) {
  Vector6d xi;
  xi << 0.1, -0.2, 0.3, 0.4, -0.5, 0.6;
  for (auto _ : state) {
    benchmark::DoNotOptimize(dlslam::SE3d::Exp(xi));
    xi[0] += 1e-9;
  }
}
BENCHMARK(BM_SE3Exp);

void BM_SE3Log(benchmark::State& state) {
  Vector6d xi;
  xi << 0.1, -0.2, 0.3, 0.4, -0.5, 0.6;
  const dlslam::SE3d T = dlslam::SE3d::Exp(xi);
  for (auto _ : state) benchmark::DoNotOptimize(T.Log());
}
BENCHMARK(BM_SE3Log);

void BM_SE3TransformPoint(benchmark::State& state) {
  Vector6d xi;
  xi << 0.1, -0.2, 0.3, 0.4, -0.5, 0.6;
  const dlslam::SE3d T = dlslam::SE3d::Exp(xi);
  Eigen::Vector3d p(0.3, 0.2, 2.0);
  for (auto _ : state) {
    p = T * p;
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_SE3TransformPoint);

}  // namespace

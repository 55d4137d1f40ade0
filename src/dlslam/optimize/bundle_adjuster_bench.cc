// Ceres vs our sparse LM on a local bundle of the size local mapping solves:
// 20 keyframes (5 fixed), 5000 points, ~19000 observations, 0.5 px noise and
// 3 % outliers, with the default two-pass schedule (5 + 10 iterations).

#include <benchmark/benchmark.h>

#include "dlslam/optimize/bundle_adjuster.h"
#include "tests/support/synthetic_bundle.h"

namespace dlslam {
namespace {

void BM_LocalBundle(benchmark::State& state, BundleSolver solver) {
  testing::SyntheticBundleOptions o;
  o.poses = static_cast<int>(state.range(0));
  o.fixed_poses = o.poses / 4;
  o.points = static_cast<int>(state.range(1));
  o.outlier_fraction = 0.03;
  const testing::SyntheticBundle bundle = testing::MakeSyntheticBundle(o);
  BundleAdjusterOptions options;
  options.solver = solver;
  double final_cost = 0;
  int iterations = 0;
  for (auto _ : state) {
    BundleProblem problem = bundle.problem;
    const BundleSummary s = SolveBundle(&problem, options);
    final_cost = s.final_cost;
    iterations = s.iterations;
    benchmark::DoNotOptimize(problem.points.data());
  }
  state.counters["observations"] = static_cast<double>(bundle.problem.observations.size());
  state.counters["final_cost"] = final_cost;
  state.counters["iterations"] = iterations;
}

BENCHMARK_CAPTURE(BM_LocalBundle, ceres, BundleSolver::kCeres)
    ->Args({10, 2000})->Args({20, 5000})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LocalBundle, lm, BundleSolver::kLm)
    ->Args({10, 2000})->Args({20, 5000})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dlslam

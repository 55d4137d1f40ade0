// Pose-graph optimisation of an essential graph the size loop closing meets:
// N keyframes on a drifting loop, odometry edges i -> i+1, covisibility edges
// to the next 2..k keyframes and a few loop edges across the trajectory, all
// measured with noise; start poses are the chained (drifted) odometry.
// Args: {keyframes, covisibility neighbours, loop edges}.

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>

#include "dlslam/optimize/pose_graph.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

PoseGraph MakeEssentialGraph(int n, int neighbours, int loops) {
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0, 0.003);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<SE3d> truth;
  for (int k = 0; k < n; ++k) {
    const double angle = 6 * std::numbers::pi * k / n;  // three laps of a 5 m circle
    const SE3d world_from_cam(SO3d::Exp(Eigen::Vector3d(0, angle, 0)),
                              Eigen::Vector3d(5 * std::cos(angle), 0.001 * k, 5 * std::sin(angle)));
    truth.push_back(world_from_cam.Inverse());
  }
  const auto measure = [&](int to, int from) {
    Vector6d e;
    for (int i = 0; i < 6; ++i) e[i] = noise(rng);
    return SE3d::Exp(e) * truth[to] * truth[from].Inverse();
  };
  PoseGraph g;
  g.fixed.assign(n, false);
  g.fixed[0] = true;
  g.cam_from_world.push_back(truth[0]);
  for (int k = 0; k + 1 < n; ++k) {
    g.edges.push_back({k, k + 1, measure(k + 1, k), 1.0});
    g.cam_from_world.push_back(g.edges.back().to_from_from * g.cam_from_world.back());
  }
  for (int k = 0; k < n; ++k) {
    for (int j = 2; j <= neighbours && k + j < n; ++j) g.edges.push_back({k, k + j, measure(k + j, k), 1.0});
  }
  for (int l = 0; l < loops; ++l) {
    // Same place on another lap: n / 3 keyframes apart.
    const int from = pick(rng) % (2 * n / 3);
    g.edges.push_back({from + n / 3, from, measure(from, from + n / 3), 1.0});
  }
  return g;
}

void BM_PoseGraph(benchmark::State& state) {
  const PoseGraph graph = MakeEssentialGraph(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                                             static_cast<int>(state.range(2)));
  PoseGraphSummary summary;
  for (auto _ : state) {
    PoseGraph g = graph;
    summary = OptimizePoseGraph(&g);
    benchmark::DoNotOptimize(g.cam_from_world.data());
  }
  state.counters["edges"] = static_cast<double>(graph.edges.size());
  state.counters["iterations"] = summary.iterations;
  state.counters["initial_cost"] = summary.initial_cost;
  state.counters["final_cost"] = summary.final_cost;
}

// ~300 keyframes / ~1500 edges (an essential graph), then a 1000-keyframe chain.
BENCHMARK(BM_PoseGraph)->Args({300, 5, 100})->Args({1000, 3, 200})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dlslam

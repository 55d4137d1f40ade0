#include "dlslam/optimize/pose_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "dlslam/util/check.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Measured cam_to_from_cam_from of two cam_from_world poses.
SE3d Relative(const SE3d& to, const SE3d& from) { return to * from.Inverse(); }

// N cameras on a circle of radius 3 m, turning about the vertical as they go.
std::vector<SE3d> CirclePoses(int n) {
  std::vector<SE3d> poses;
  for (int k = 0; k < n; ++k) {
    const double angle = 2 * std::numbers::pi * k / n;
    const SO3d world_rotation = SO3d::Exp(Eigen::Vector3d(0, angle, 0.05 * std::sin(angle)));
    const Eigen::Vector3d position(3 * std::cos(angle), 0.2 * std::sin(2 * angle), 3 * std::sin(angle));
    const SE3d world_from_cam(world_rotation, position);
    poses.push_back(world_from_cam.Inverse());
  }
  return poses;
}

// Odometry i -> i+1, a skip edge i -> i+2 and a loop edge (n-1) -> 0, all exact.
PoseGraph ConsistentGraph(const std::vector<SE3d>& truth) {
  PoseGraph g;
  g.cam_from_world = truth;
  g.fixed.assign(truth.size(), false);
  g.fixed[0] = true;
  const int n = static_cast<int>(truth.size());
  for (int k = 0; k + 1 < n; ++k) g.edges.push_back({k, k + 1, Relative(truth[k + 1], truth[k]), 1.0});
  for (int k = 0; k + 2 < n; k += 3) g.edges.push_back({k, k + 2, Relative(truth[k + 2], truth[k]), 0.5});
  g.edges.push_back({n - 1, 0, Relative(truth[0], truth[n - 1]), 1.0});
  return g;
}

double PositionError(const SE3d& a, const SE3d& b) {
  return (a.Inverse().translation() - b.Inverse().translation()).norm();
}
double MaxPoseDifference(const SE3d& a, const SE3d& b) { return (a.Inverse() * b).Log().cwiseAbs().maxCoeff(); }

double CostOf(const PoseGraph& g) {
  double cost = 0;
  for (const auto& e : g.edges) {
    cost += 0.5 * PoseGraphResidual(e, g.cam_from_world[e.to], g.cam_from_world[e.from]).squaredNorm();
  }
  return cost;
}

TEST(PoseGraph, ConsistentGraphStaysPut) {
  const std::vector<SE3d> truth = CirclePoses(12);
  PoseGraph g = ConsistentGraph(truth);
  const PoseGraphSummary s = OptimizePoseGraph(&g);
  EXPECT_LT(s.initial_cost, 1e-25);
  EXPECT_LT(s.final_cost, 1e-25);
  EXPECT_TRUE(s.converged);
  for (std::size_t k = 0; k < truth.size(); ++k) {
    EXPECT_LT(MaxPoseDifference(g.cam_from_world[k], truth[k]), 1e-12) << k;
  }
}

TEST(PoseGraph, ConsistentGraphIsRecoveredFromAPerturbedStart) {
  const std::vector<SE3d> truth = CirclePoses(12);
  PoseGraph g = ConsistentGraph(truth);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.05);
  for (std::size_t k = 1; k < truth.size(); ++k) {
    Vector6d d;
    for (int i = 0; i < 6; ++i) d[i] = noise(rng);
    g.cam_from_world[k] = SE3d::Exp(d) * truth[k];
  }
  const PoseGraphSummary s = OptimizePoseGraph(&g);
  EXPECT_GT(s.initial_cost, 1e-3);
  EXPECT_LT(s.final_cost, 1e-20);
  EXPECT_TRUE(s.converged);
  for (std::size_t k = 0; k < truth.size(); ++k) EXPECT_LT(MaxPoseDifference(g.cam_from_world[k], truth[k]), 1e-9) << k;
}

// Cameras on the x axis without rotation, every odometry edge measuring b too
// far in x, the loop edge exact. The residuals are then linear in the
// translations and the least-squares answer is known in closed form: with
// loop weight w, pose k moves to truth + k c with c = b / (1 + w^2 (n - 1)).
TEST(PoseGraph, BiasedLineLoopSpreadsTheMisclosureAsLeastSquaresDoes) {
  const int n = 10;
  const double b = 0.03;
  for (const double w : {1.0, 2.0}) {
    std::vector<SE3d> truth;
    for (int k = 0; k < n; ++k) truth.emplace_back(SO3d(), Eigen::Vector3d(0.4 * k + 0.05 * k * k, 0, 0));
    PoseGraph g;
    g.fixed.assign(n, false);
    g.fixed[0] = true;
    g.cam_from_world.push_back(truth[0]);
    for (int k = 0; k + 1 < n; ++k) {
      const SE3d measured = Relative(truth[k + 1], truth[k]) * SE3d(SO3d(), Eigen::Vector3d(b, 0, 0));
      g.edges.push_back({k, k + 1, measured, 1.0});
      g.cam_from_world.push_back(measured * g.cam_from_world.back());  // chained odometry
    }
    g.edges.push_back({n - 1, 0, Relative(truth[0], truth[n - 1]), w});
    const double c = b / (1 + w * w * (n - 1));
    // The default tolerances stop on the cost, which is flat near the
    // minimum: within 1e-6 m there, to 1e-10 m (the cost's rounding floor) with tight ones.
    for (const double tolerance : {1e-6, 1e-10}) {
      PoseGraph solved = g;
      PoseGraphOptions options;
      if (tolerance < 1e-6) {
        options.max_iterations = 100;
        options.function_tolerance = options.parameter_tolerance = options.gradient_tolerance = 1e-16;
      }
      const PoseGraphSummary s = OptimizePoseGraph(&solved, options);
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d expected = truth[k].translation() + Eigen::Vector3d(k * c, 0, 0);
        EXPECT_LT((solved.cam_from_world[k].translation() - expected).norm(), tolerance) << "w " << w << " pose " << k;
        EXPECT_LT(solved.cam_from_world[k].so3().Log().norm(), 1e-12);
      }
      EXPECT_NEAR(s.final_cost, CostOf(solved), 1e-14);
    }
  }
}

struct DriftingLoop {
  std::vector<SE3d> truth;
  PoseGraph graph;
};

// Odometry with a steady heading bias plus noise, chained into the start
// poses; one exact loop edge from the last pose to the first.
DriftingLoop MakeDriftingLoop(int n, unsigned seed) {
  DriftingLoop d;
  d.truth = CirclePoses(n);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 0.002);
  PoseGraph& g = d.graph;
  g.fixed.assign(n, false);
  g.fixed[0] = true;
  g.cam_from_world.push_back(d.truth[0]);
  for (int k = 0; k + 1 < n; ++k) {
    Vector6d e;
    for (int i = 0; i < 6; ++i) e[i] = noise(rng);
    e[4] += 0.01;  // heading drift
    const SE3d measured = SE3d::Exp(e) * Relative(d.truth[k + 1], d.truth[k]);
    g.edges.push_back({k, k + 1, measured, 1.0});
    g.cam_from_world.push_back(measured * g.cam_from_world.back());
  }
  g.edges.push_back({n - 1, 0, Relative(d.truth[0], d.truth[n - 1]), 1.0});
  return d;
}

double MaxPositionError(const std::vector<SE3d>& poses, const std::vector<SE3d>& truth) {
  double e = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) e = std::max(e, PositionError(poses[k], truth[k]));
  return e;
}

TEST(PoseGraph, LoopEdgeClosesADriftingLoop) {
  DriftingLoop d = MakeDriftingLoop(40, 7);
  const double drift = MaxPositionError(d.graph.cam_from_world, d.truth);
  ASSERT_GT(drift, 0.5);  // the test means something only if the chain drifted
  const PoseGraphSummary s = OptimizePoseGraph(&d.graph);
  EXPECT_TRUE(s.converged);
  EXPECT_LT(s.final_cost, 0.01 * s.initial_cost);
  const double after = MaxPositionError(d.graph.cam_from_world, d.truth);
  EXPECT_LT(after, 0.1 * drift) << "drift " << drift << " after " << after;
  // The loop edge now agrees with the poses about as well as any odometry edge.
  const PoseGraphEdge& loop = d.graph.edges.back();
  EXPECT_LT(PoseGraphResidual(loop, d.graph.cam_from_world[loop.to], d.graph.cam_from_world[loop.from]).norm(), 0.05);
  EXPECT_NEAR(s.final_cost, CostOf(d.graph), 1e-12);
}

TEST(PoseGraph, FixedPosesDoNotMoveAndUntouchedPosesStay) {
  DriftingLoop d = MakeDriftingLoop(20, 11);
  d.graph.fixed[7] = true;
  d.graph.cam_from_world.push_back(SE3d::Exp(Vector6d::Constant(0.3)));  // no edge touches it
  d.graph.fixed.push_back(false);
  const PoseGraph before = d.graph;
  OptimizePoseGraph(&d.graph);
  for (const int k : {0, 7, 20}) {
    EXPECT_EQ(d.graph.cam_from_world[k].matrix(), before.cam_from_world[k].matrix()) << k;
  }
  EXPECT_NE(d.graph.cam_from_world[5].matrix(), before.cam_from_world[5].matrix());
}

TEST(PoseGraph, GraphWithoutEdgesIsLeftAlone) {
  PoseGraph g;
  g.cam_from_world = CirclePoses(3);
  g.fixed.assign(3, false);
  const PoseGraph before = g;
  const PoseGraphSummary s = OptimizePoseGraph(&g);
  EXPECT_TRUE(s.converged);
  EXPECT_EQ(s.iterations, 0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(g.cam_from_world[k].matrix(), before.cam_from_world[k].matrix());
}

TEST(PoseGraph, MalformedGraphsAreRejected) {
  const PoseGraph good = ConsistentGraph(CirclePoses(5));
  const auto expect_error = [](PoseGraph g, const char* what) {
    EXPECT_THROW(OptimizePoseGraph(&g), Error) << what;
  };
  PoseGraph g = good;
  g.fixed.pop_back();
  expect_error(g, "sizes differ");
  g = good;
  g.edges[1].to = 5;
  expect_error(g, "index past the end");
  g = good;
  g.edges[1].from = -1;
  expect_error(g, "negative index");
  g = good;
  g.edges[2].to = g.edges[2].from;
  expect_error(g, "self edge");
  g = good;
  g.edges[0].weight = 0;
  expect_error(g, "zero weight");
  g = good;
  g.edges[0].weight = NAN;
  expect_error(g, "NaN weight");
  g = good;
  g.fixed.assign(5, false);
  expect_error(g, "nothing fixed");
  EXPECT_THROW(OptimizePoseGraph(nullptr), Error);
}

TEST(PoseGraph, OptionsAreChecked) {
  PoseGraph g = ConsistentGraph(CirclePoses(5));
  PoseGraphOptions o;
  o.max_iterations = -1;
  EXPECT_THROW(OptimizePoseGraph(&g, o), Error);
  o = {};
  o.function_tolerance = 1.5;
  EXPECT_THROW(OptimizePoseGraph(&g, o), Error);
  o = {};
  o.threads = 0;
  EXPECT_THROW(OptimizePoseGraph(&g, o), Error);
  EXPECT_NO_THROW(PoseGraphOptions{}.Check());
}

}  // namespace
}  // namespace dlslam

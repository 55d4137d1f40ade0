#include "dlslam/optimize/bundle_adjuster.h"

#include <gtest/gtest.h>

#include <atomic>
#include <random>
#include <string>

#include "dlslam/util/check.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Five cameras along a line looking at points 2-5 m ahead; the first two
// fixed. Truth is kept to compare against.
struct Scene {
  BundleProblem problem;
  std::vector<SE3d> true_poses;
  std::vector<Eigen::Vector3d> true_points;
  std::vector<bool> is_outlier;
};

Scene MakeScene(double pixel_noise, double outlier_fraction, unsigned seed) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> n(0, 1);
  s.problem.camera = CameraPreset("freiburg3");
  for (int i = 0; i < 5; ++i) {
    Vector6d xi;
    xi << -0.1 * i, 0.02 * i, 0.05 * i, 0.01 * i, 0.03 * i, 0;
    s.true_poses.push_back(SE3d::Exp(xi));
  }
  for (int j = 0; j < 300; ++j) {
    s.true_points.emplace_back(-1.5 + 3 * u(rng), -1 + 2 * u(rng), 2 + 3 * u(rng));
  }
  for (int i = 0; i < 5; ++i) {
    BundleProblem::Pose pose;
    pose.fixed = i < 2;
    Vector6d d;
    for (int k = 0; k < 6; ++k) d[k] = pose.fixed ? 0 : 0.01 * n(rng);
    pose.cam_from_world = SE3d::Exp(d) * s.true_poses[i];
    s.problem.poses.push_back(pose);
  }
  for (const auto& p : s.true_points) s.problem.points.push_back(p + 0.02 * Eigen::Vector3d(n(rng), n(rng), n(rng)));
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 300; ++j) {
      const Eigen::Vector3d pc = s.true_poses[i] * s.true_points[j];
      const Eigen::Vector2d uv = s.problem.camera.Project(pc);
      if (uv.x() < 0 || uv.y() < 0 || uv.x() >= 640 || uv.y() >= 480) continue;
      BundleProblem::Observation o;
      o.pose = i;
      o.point = j;
      o.pixel = uv + pixel_noise * Eigen::Vector2d(n(rng), n(rng));
      o.right_u = (j % 3 == 0) ? -1.0 : o.pixel.x() - s.problem.camera.bf / pc.z() + pixel_noise * n(rng);
      const bool outlier = u(rng) < outlier_fraction;
      if (outlier) o.pixel += Eigen::Vector2d(30 + 30 * u(rng), -40);
      s.problem.observations.push_back(o);
      s.is_outlier.push_back(outlier);
    }
  }
  return s;
}

double MaxPoseError(const Scene& s) {
  double e = 0;
  for (std::size_t i = 0; i < s.true_poses.size(); ++i) {
    e = std::max(e, (s.problem.poses[i].cam_from_world.Inverse().translation() - s.true_poses[i].Inverse().translation()).norm());
  }
  return e;
}

// Every behaviour is checked for both solvers.
class BundleAdjuster : public ::testing::TestWithParam<BundleSolver> {
 protected:
  BundleSummary Solve(BundleProblem* problem) const {
    BundleAdjusterOptions options;
    options.solver = GetParam();
    return SolveBundle(problem, options);
  }
};

INSTANTIATE_TEST_SUITE_P(Solvers, BundleAdjuster, ::testing::Values(BundleSolver::kCeres, BundleSolver::kLm),
                         [](const auto& solver_info) { return std::string(ToString(solver_info.param)); });

TEST_P(BundleAdjuster, RecoversPosesAndPointsFromExactObservations) {
  Scene s = MakeScene(0.0, 0.0, 1);
  const BundleSummary summary = Solve(&s.problem);
  EXPECT_LT(MaxPoseError(s), 1e-6);
  // Points seen once without depth are free along their ray: skip them.
  std::vector<int> constraints(s.true_points.size(), 0);
  for (const auto& o : s.problem.observations) constraints[o.point] += o.right_u >= 0 ? 2 : 1;
  double point_error = 0;
  for (std::size_t j = 0; j < s.true_points.size(); ++j) {
    if (constraints[j] < 2) continue;
    point_error = std::max(point_error, (s.problem.points[j] - s.true_points[j]).norm());
  }
  EXPECT_LT(point_error, 1e-5);
  EXPECT_EQ(summary.outliers, 0);
  EXPECT_LT(summary.final_cost, 1e-8 * summary.initial_cost + 1e-12);
}

TEST_P(BundleAdjuster, FixedPosesDoNotMove) {
  Scene s = MakeScene(1.0, 0.0, 2);
  const SE3d before = s.problem.poses[0].cam_from_world;
  Solve(&s.problem);
  EXPECT_EQ(s.problem.poses[0].cam_from_world.matrix(), before.matrix());
}

TEST_P(BundleAdjuster, FlagsOutliersAndStaysAccurate) {
  Scene s = MakeScene(0.5, 0.1, 3);
  const BundleSummary summary = Solve(&s.problem);
  int caught = 0, false_alarms = 0, outliers = 0;
  for (std::size_t k = 0; k < s.is_outlier.size(); ++k) {
    outliers += s.is_outlier[k];
    caught += s.is_outlier[k] && summary.outlier[k];
    false_alarms += !s.is_outlier[k] && summary.outlier[k];
  }
  ASSERT_GT(outliers, 50);
  EXPECT_EQ(caught, outliers);
  EXPECT_LT(false_alarms, 0.1 * (static_cast<int>(s.is_outlier.size()) - outliers));
  EXPECT_LT(MaxPoseError(s), 0.005);
}

double TotalChi2(const BundleProblem& p) {
  double chi2 = 0;
  for (const auto& o : p.observations) chi2 += ObservationChi2(p, o);
  return chi2;
}

TEST_P(BundleAdjuster, AbortFlagAlreadySetReturnsAtOnce) {
  Scene s = MakeScene(1.0, 0.0, 4);
  const double chi2_before = TotalChi2(s.problem);
  const std::atomic<bool> abort(true);
  BundleAdjusterOptions options;
  options.solver = GetParam();
  options.abort = &abort;
  const BundleSummary summary = SolveBundle(&s.problem, options);
  EXPECT_TRUE(summary.aborted);
  EXPECT_LE(summary.iterations, 1);
  EXPECT_GT(summary.initial_cost, 0.0);
  EXPECT_LE(summary.final_cost, summary.initial_cost);
  EXPECT_LE(TotalChi2(s.problem), chi2_before * (1 + 1e-12));
  EXPECT_EQ(summary.outlier.size(), s.problem.observations.size());
}

TEST_P(BundleAdjuster, AbortFlagLeftClearChangesNothing) {
  Scene with_flag = MakeScene(1.0, 0.05, 5);
  Scene without = with_flag;
  const std::atomic<bool> abort(false);
  BundleAdjusterOptions options;
  options.solver = GetParam();
  options.abort = &abort;
  const BundleSummary summary = SolveBundle(&with_flag.problem, options);
  const BundleSummary reference = Solve(&without.problem);
  EXPECT_FALSE(summary.aborted);
  EXPECT_FALSE(reference.aborted);
  EXPECT_EQ(summary.iterations, reference.iterations);
  EXPECT_EQ(summary.final_cost, reference.final_cost);
  for (std::size_t i = 0; i < with_flag.problem.poses.size(); ++i) {
    EXPECT_EQ(with_flag.problem.poses[i].cam_from_world.matrix(), without.problem.poses[i].cam_from_world.matrix());
  }
}

TEST_P(BundleAdjuster, EmptyProblemIsANoOp) {
  BundleProblem p;
  p.camera = CameraPreset("fr3");
  EXPECT_EQ(Solve(&p).iterations, 0);
}

TEST(BundleSolver, ParsesItsNamesAndRejectsOthers) {
  EXPECT_EQ(ParseBundleSolver("ceres"), BundleSolver::kCeres);
  EXPECT_EQ(ParseBundleSolver("lm"), BundleSolver::kLm);
  EXPECT_STREQ(ToString(ParseBundleSolver("lm")), "lm");
  EXPECT_THROW(ParseBundleSolver("g2o"), Error);
}

}  // namespace
}  // namespace dlslam

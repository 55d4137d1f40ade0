// The hand-written LM against Ceres: same problem, same minimum.

#include <gtest/gtest.h>

#include "dlslam/optimize/bundle_adjuster.h"
#include "dlslam/util/check.h"
#include "tests/support/synthetic_bundle.h"

namespace dlslam {
namespace {

// Both solvers run to convergence (many iterations, tight tolerance).
BundleAdjusterOptions Converged(BundleSolver solver) {
  BundleAdjusterOptions options;
  options.solver = solver;
  options.first_pass_iterations = 100;
  options.second_pass_iterations = 100;
  options.function_tolerance = 1e-14;
  return options;
}

testing::SyntheticBundleOptions SmallBundle() {
  testing::SyntheticBundleOptions o;
  o.poses = 8;
  o.fixed_poses = 2;
  o.points = 400;
  o.pixel_noise = 0.7;
  o.outlier_fraction = 0.05;
  o.seed = 11;
  return o;
}

TEST(LmBundleAdjuster, ConvergesToTheCeresSolution) {
  testing::SyntheticBundle with_ceres = testing::MakeSyntheticBundle(SmallBundle());
  testing::SyntheticBundle with_lm = with_ceres;
  const BundleSummary ceres = SolveBundle(&with_ceres.problem, Converged(BundleSolver::kCeres));
  const BundleSummary lm = SolveBundle(&with_lm.problem, Converged(BundleSolver::kLm));
  ASSERT_GT(ceres.outliers, 10);  // the robust pass and the classification matter
  EXPECT_NEAR(lm.final_cost, ceres.final_cost, 1e-6 * ceres.final_cost);
  double pose_diff = 0;
  for (std::size_t i = 0; i < with_lm.problem.poses.size(); ++i) {
    const SE3d delta = with_lm.problem.poses[i].cam_from_world * with_ceres.problem.poses[i].cam_from_world.Inverse();
    pose_diff = std::max(pose_diff, delta.Log().norm());
  }
  EXPECT_LT(pose_diff, 1e-6);
  // Points: those the observations determine. Left out: points seen by one
  // keypoint without depth (free along the ray) and the few whose rays are
  // nearly parallel, which both solvers send towards infinity.
  std::vector<int> rows(with_lm.problem.points.size(), 0);
  for (std::size_t k = 0; k < ceres.outlier.size(); ++k) {
    const auto& o = with_lm.problem.observations[k];
    if (!ceres.outlier[k]) rows[o.point] += o.right_u >= 0 ? 3 : 2;
  }
  std::vector<bool> determined(rows.size());
  int compared = 0, within_1e6 = 0;
  double point_diff = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    determined[j] = rows[j] >= 3 && (with_ceres.problem.points[j] - with_ceres.true_points[j]).norm() < 1.0;
    if (!determined[j]) continue;
    ++compared;
    const double d = (with_lm.problem.points[j] - with_ceres.problem.points[j]).norm();
    within_1e6 += d < 1e-6;
    point_diff = std::max(point_diff, d);
  }
  EXPECT_GT(compared, 300);
  EXPECT_GT(within_1e6, 0.9 * compared);
  // Far points seen across a short baseline are weakly determined in depth:
  // a 1e-6 agreement in the cost leaves them a few micrometres apart.
  EXPECT_LT(point_diff, 1e-4);
  int flags_differ = 0;
  for (std::size_t k = 0; k < ceres.outlier.size(); ++k) {
    if (determined[with_lm.problem.observations[k].point]) flags_differ += lm.outlier[k] != ceres.outlier[k];
  }
  EXPECT_EQ(flags_differ, 0);
  // ... and that minimum is near the truth (the solvers did not agree on a
  // wrong answer).
  double truth_error = 0;
  for (std::size_t i = 0; i < with_lm.problem.poses.size(); ++i) {
    truth_error = std::max(
        truth_error, (with_lm.problem.poses[i].cam_from_world * with_lm.true_poses[i].Inverse()).Log().norm());
  }
  EXPECT_LT(truth_error, 0.01);
}

// A point observed twice in one keyframe (two keypoints matched to it) puts
// both observations' Schur terms into one diagonal block: the solver's
// special case there must still give Ceres' minimum.
TEST(LmBundleAdjuster, TwoObservationsOfAPointInOneKeyframeMatchCeres) {
  testing::SyntheticBundleOptions o = SmallBundle();
  o.outlier_fraction = 0;
  testing::SyntheticBundle with_ceres = testing::MakeSyntheticBundle(o);
  auto& observations = with_ceres.problem.observations;
  const std::size_t n = observations.size();
  int duplicated = 0;
  for (std::size_t k = 0; k < n; k += 7) {
    if (with_ceres.problem.poses[observations[k].pose].fixed) continue;
    BundleProblem::Observation twin = observations[k];
    twin.pixel += Eigen::Vector2d(0.8, -0.5);  // a second keypoint a pixel away
    observations.push_back(twin);
    ++duplicated;
  }
  ASSERT_GT(duplicated, 100);
  testing::SyntheticBundle with_lm = with_ceres;
  const BundleSummary ceres = SolveBundle(&with_ceres.problem, Converged(BundleSolver::kCeres));
  const BundleSummary lm = SolveBundle(&with_lm.problem, Converged(BundleSolver::kLm));
  // A wrong Schur complement still reaches the minimum (steps are only
  // accepted when they lower the cost), but slowly: 60 iterations against
  // Ceres' 16 when the twin's term was left out; 15 with it.
  EXPECT_LE(lm.iterations, ceres.iterations + 5);
  EXPECT_NEAR(lm.final_cost, ceres.final_cost, 1e-6 * ceres.final_cost);
  for (std::size_t i = 0; i < with_lm.problem.poses.size(); ++i) {
    const SE3d delta = with_lm.problem.poses[i].cam_from_world * with_ceres.problem.poses[i].cam_from_world.Inverse();
    EXPECT_LT(delta.Log().norm(), 1e-6) << "pose " << i;
  }
}

TEST(LmBundleAdjuster, LowersTheCostWithinTheDefaultIterations) {
  testing::SyntheticBundleOptions o = SmallBundle();
  o.pose_perturbation = 0.03;
  testing::SyntheticBundle s = testing::MakeSyntheticBundle(o);
  BundleAdjusterOptions options;
  options.solver = BundleSolver::kLm;
  const BundleSummary summary = SolveBundle(&s.problem, options);
  EXPECT_GT(summary.iterations, 0);
  EXPECT_LT(summary.final_cost, 0.1 * summary.initial_cost);
}

TEST(LmBundleAdjuster, RejectsObservationsOfMissingEntities) {
  testing::SyntheticBundle s = testing::MakeSyntheticBundle(SmallBundle());
  s.problem.observations[3].point = static_cast<int>(s.problem.points.size());
  EXPECT_THROW(SolveBundleLm(&s.problem, {}), Error);
}

TEST(LmBundleAdjuster, AllPosesFixedMovesOnlyPoints) {
  testing::SyntheticBundleOptions o = SmallBundle();
  o.fixed_poses = o.poses;
  testing::SyntheticBundle s = testing::MakeSyntheticBundle(o);
  const std::vector<BundleProblem::Pose> before = s.problem.poses;
  SolveBundleLm(&s.problem, Converged(BundleSolver::kLm));
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(s.problem.poses[i].cam_from_world.matrix(), before[i].cam_from_world.matrix());
  }
  // Point 1 has depth (every point but each third): close to the truth.
  EXPECT_LT((s.problem.points[1] - s.true_points[1]).norm(), 0.05);
}

}  // namespace
}  // namespace dlslam

#include "dlslam/optimize/pose_optimizer.h"

#include <gtest/gtest.h>

#include "dlslam/util/check.h"
#include "tests/support/numeric_diff.h"
#include "tests/support/pose_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

using testing::MakePoseScene;
using testing::PerturbPose;
using testing::PoseScene;

double TranslationError(const SE3d& a, const SE3d& b) {
  return (a.Inverse().translation() - b.Inverse().translation()).norm();
}
double RotationErrorRad(const SE3d& a, const SE3d& b) { return (a.so3().Inverse() * b.so3()).Log().norm(); }

TEST(PoseOptimizer, JacobianMatchesNumericDifferences) {
  const PoseScene s = MakePoseScene(20, 0, 0, 1);
  for (const auto& obs : s.observations) {
    ObservationLinearization lin;
    ASSERT_TRUE(LinearizeObservation(s.camera, s.cam_from_world, obs, true, &lin));
    const auto f = [&](const Vector6d& d) {
      ObservationLinearization l;
      LinearizeObservation(s.camera, SE3d::Exp(d) * s.cam_from_world, obs, false, &l);
      return l.residual;
    };
    const Eigen::Matrix<double, 3, 6> numeric = testing::NumericJacobian<3, 6>(f, Vector6d::Zero());
    EXPECT_LT((numeric - lin.jacobian).norm(), 1e-5 * std::max(1.0, lin.jacobian.norm()));
  }
}

TEST(PoseOptimizer, ExactDataGivesExactPose) {
  const PoseScene s = MakePoseScene(100, 0, 0, 2);
  const auto r = OptimizePose(s.camera, PerturbPose(s.cam_from_world, 0.1, 0.05), s.observations);
  EXPECT_LT(TranslationError(r.cam_from_world, s.cam_from_world), 1e-9);
  EXPECT_LT(RotationErrorRad(r.cam_from_world, s.cam_from_world), 1e-10);
  EXPECT_EQ(r.num_inliers, 100);
}

TEST(PoseOptimizer, RejectsWrongMatchesAndStaysAccurate) {
  const PoseScene s = MakePoseScene(300, 0.3, 1.0, 3);
  const auto r = OptimizePose(s.camera, PerturbPose(s.cam_from_world, 0.05, 0.03), s.observations);
  EXPECT_LT(TranslationError(r.cam_from_world, s.cam_from_world), 0.01);
  EXPECT_LT(RotationErrorRad(r.cam_from_world, s.cam_from_world), 0.003);
  int wrong_kept = 0, right_dropped = 0, outliers = 0;
  for (std::size_t i = 0; i < s.observations.size(); ++i) {
    outliers += s.is_outlier[i];
    wrong_kept += s.is_outlier[i] && r.inliers[i];
    right_dropped += !s.is_outlier[i] && !r.inliers[i];
  }
  ASSERT_GT(outliers, 60);
  EXPECT_LE(wrong_kept, 2);  // a random pixel can land near the true one
  // ~5 % of true matches exceed the 95 % chi-square gate by construction.
  EXPECT_LT(right_dropped, 0.1 * (300 - outliers));
}

TEST(PoseOptimizer, TooFewObservationsLeavesPoseUnchanged) {
  const PoseScene s = MakePoseScene(2, 0, 0, 4);
  const SE3d start = PerturbPose(s.cam_from_world, 0.1, 0.1);
  const auto r = OptimizePose(s.camera, start, s.observations);
  EXPECT_EQ(r.cam_from_world.matrix(), start.matrix());
  EXPECT_EQ(r.num_inliers, 0);
}

TEST(PoseOptimizer, PointsBehindTheCameraAreOutliers) {
  PoseScene s = MakePoseScene(50, 0, 0, 5);
  s.observations[0].point_world = s.cam_from_world.Inverse() * Eigen::Vector3d(0, 0, -2);
  const auto r = OptimizePose(s.camera, s.cam_from_world, s.observations);
  EXPECT_FALSE(r.inliers[0]);
  EXPECT_EQ(r.num_inliers, 49);
}

TEST(PoseOptimizer, InvalidOptionsAreRejected) {
  PoseOptimizerOptions o;
  o.rounds = 0;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam

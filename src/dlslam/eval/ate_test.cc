#include "dlslam/eval/ate.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

using ::testing::HasSubstr;

// A curved 3D path sampled every `dt` seconds from `t0`.
Trajectory Curve(int n, double t0, double dt) {
  Trajectory t;
  for (int k = 0; k < n; ++k) {
    const double s = k * dt;
    const Eigen::Vector3d p(std::sin(0.7 * s), std::cos(0.4 * s), 0.3 * s);
    const SO3d r = SO3d::Exp(Eigen::Vector3d(0.1 * s, -0.2, 0.05 * s));
    t.emplace_back(t0 + s, SE3d(r, p));
  }
  return t;
}

// Each pose moved into another world frame: world2_from_world * pose.
Trajectory InOtherWorld(const Trajectory& t, const SE3d& world2_from_world) {
  Trajectory out;
  for (const StampedPose& p : t) out.emplace_back(p.timestamp, world2_from_world * p.world_from_cam());
  return out;
}

const SE3d kOtherWorld(SO3d::Exp(Eigen::Vector3d(0.4, -1.2, 2.0)), Eigen::Vector3d(3, -1, 0.5));

std::string ErrorOf(const Trajectory& gt, const Trajectory& est, const AteOptions& options = {}) {
  try {
    ComputeAte(gt, est, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(AteTest, SameTrajectoryInAnotherWorldFrameHasZeroError) {
  const Trajectory gt = Curve(100, 1305031102.1753, 0.03);
  const AteResult r = ComputeAte(gt, InOtherWorld(gt, kOtherWorld));
  EXPECT_EQ(r.pairs, 100u);
  EXPECT_LT(r.error.max, 1e-12);
  // The alignment is the inverse of the frame change.
  const Eigen::Matrix3d expected_r = kOtherWorld.Inverse().rotationMatrix();
  EXPECT_LT((r.gt_from_est.rotation - expected_r).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((r.gt_from_est.translation - kOtherWorld.Inverse().translation()).norm(), 1e-12);
  ASSERT_EQ(r.per_pair.size(), 100u);
  EXPECT_DOUBLE_EQ(r.per_pair[3].gt_timestamp, gt[3].timestamp);
}

TEST(AteTest, ScaleAndOffsetUndoAMonocularEstimateOnAnotherClock) {
  const Trajectory gt = Curve(80, 1000.0, 0.05);
  Trajectory est = gt;
  for (StampedPose& p : est) {
    p.translation *= 0.25;
    p.timestamp -= 0.725;  // not a multiple of the 0.05 s step: nothing within 0.02 s
  }
  EXPECT_THAT(ErrorOf(gt, est), HasSubstr("no overlap in time between GT and EST within max-diff 0.02 s"));
  const AteResult r = ComputeAte(gt, est, {.max_diff = 0.02, .offset = 0.725, .scale = 4.0});
  EXPECT_EQ(r.pairs, 80u);
  EXPECT_LT(r.error.rmse, 1e-12);
  EXPECT_DOUBLE_EQ(r.per_pair[0].est_timestamp, 999.275);  // as in the file
}

TEST(AteTest, HandCheckedTwoPointAlignment) {
  // Centred est points are +-0.5 along x, gt +-1: the best rigid fit leaves 0.5 each.
  Trajectory gt;
  Trajectory est;
  gt.emplace_back(1.0, SE3d(SO3d(), Eigen::Vector3d(0, 0, 0)));
  gt.emplace_back(2.0, SE3d(SO3d(), Eigen::Vector3d(2, 0, 0)));
  est.emplace_back(1.0, SE3d(SO3d(), Eigen::Vector3d(5, 5, 5)));
  est.emplace_back(2.0, SE3d(SO3d(), Eigen::Vector3d(5, 6, 5)));
  const AteResult r = ComputeAte(gt, est);
  EXPECT_NEAR(r.error.rmse, 0.5, 1e-12);
  EXPECT_NEAR(r.error.min, 0.5, 1e-12);
  EXPECT_NEAR(r.error.std, 0.0, 1e-12);
}

TEST(AteTest, AllEstimatePositionsIdenticalGivesFiniteErrors) {
  const Trajectory gt = Curve(10, 0.0, 0.1);
  Trajectory est = gt;
  for (StampedPose& p : est) p.translation = Eigen::Vector3d(1, 1, 1);
  const AteResult r = ComputeAte(gt, est);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const StampedPose& p : gt) mean += p.translation / 10.0;
  EXPECT_TRUE(std::isfinite(r.error.rmse));
  EXPECT_NEAR(r.per_pair[4].error, (gt[4].translation - mean).norm(), 1e-12);
}

TEST(AteTest, RefusesTooLittleInput) {
  const Trajectory gt = Curve(10, 0.0, 0.1);
  EXPECT_THAT(ErrorOf(gt, Trajectory{}), HasSubstr("estimate trajectory has 0 pose(s)"));
  EXPECT_THAT(ErrorOf(Trajectory{gt[0]}, gt), HasSubstr("ground truth trajectory has 1 pose(s)"));
  // Only one pose within max-diff.
  Trajectory est = Curve(2, 0.9, 5.0);
  EXPECT_THAT(ErrorOf(gt, est), HasSubstr("1 pose(s) matched"));
}

TEST(AteTest, RefusesBadOptionsAndValues) {
  const Trajectory gt = Curve(10, 0.0, 0.1);
  EXPECT_THAT(ErrorOf(gt, gt, {.max_diff = 0.0}), HasSubstr("max_diff"));
  EXPECT_THAT(ErrorOf(gt, gt, {.scale = -1.0}), HasSubstr("scale"));
  Trajectory bad = gt;
  bad[3].translation.x() = std::nan("");
  EXPECT_THAT(ErrorOf(gt, bad), HasSubstr("non-finite"));
  bad = gt;
  bad[3].timestamp = bad[2].timestamp;
  EXPECT_THAT(ErrorOf(gt, bad), HasSubstr("must increase"));
}

}  // namespace
}  // namespace dlslam::eval

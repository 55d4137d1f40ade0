#include "dlslam/eval/rpe.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

using ::testing::HasSubstr;

Trajectory Curve(int n, double t0, double dt) {
  Trajectory t;
  for (int k = 0; k < n; ++k) {
    const double s = k * dt;
    const Eigen::Vector3d p(std::sin(0.7 * s), std::cos(0.4 * s), 0.3 * s);
    t.emplace_back(t0 + s, SE3d(SO3d::Exp(Eigen::Vector3d(0.1 * s, -0.2, 0.05 * s)), p));
  }
  return t;
}

// Ground truth standing still at stamps 0..n-1 s; the estimate moves 0.1 m
// along x and turns 2 degrees about z per second.
void StillAndMoving(int n, Trajectory& gt, Trajectory& est) {
  for (int k = 0; k < n; ++k) {
    gt.emplace_back(k, SE3d());
    const SO3d yaw = SO3d::Exp(Eigen::Vector3d(0, 0, k * 2.0 * std::numbers::pi / 180.0));
    est.emplace_back(k, SE3d(yaw, Eigen::Vector3d(0.1 * k, 0, 0)));
  }
}

std::string ErrorOf(const Trajectory& gt, const Trajectory& est, const RpeOptions& options = {}) {
  try {
    ComputeRpe(gt, est, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(RpeTest, IdenticalUpToWorldFrameAndScaleIsZero) {
  const Trajectory gt = Curve(200, 1305031102.0, 0.033);
  const SE3d world2_from_world(SO3d::Exp(Eigen::Vector3d(1.0, 0.2, -0.5)), Eigen::Vector3d(1, 2, 3));
  Trajectory est;
  for (const StampedPose& p : gt) {
    SE3d pose = world2_from_world * p.world_from_cam();
    pose.translation() /= 3.0;  // a monocular estimate a third of the true size
    est.emplace_back(p.timestamp, pose);
  }
  const RpeResult r = ComputeRpe(gt, est, {.delta = 1.0, .scale = 3.0});
  EXPECT_GT(r.pairs, 100u);
  EXPECT_LT(r.translation.max, 1e-12);
  // arccos near 1 resolves only ~1e-8 rad: the TUM formula's own floor.
  EXPECT_LT(r.rotation_deg.max, 1e-5);
}

TEST(RpeTest, HandCheckedConstantMotion) {
  Trajectory gt;
  Trajectory est;
  StillAndMoving(5, gt, est);
  const RpeResult r = ComputeRpe(gt, est);
  // i = 0, 1, 2 pair with i + 1; i = 3 would end at the last pose, i = 4 too.
  ASSERT_EQ(r.pairs, 3u);
  EXPECT_EQ(r.per_pair[2].est_index_0, 2u);
  EXPECT_EQ(r.per_pair[2].est_index_1, 3u);
  EXPECT_NEAR(r.translation.rmse, 0.1, 1e-12);
  EXPECT_NEAR(r.rotation_deg.mean, 2.0, 1e-9);
}

TEST(RpeTest, DeltaUnitsPickDifferentPartners) {
  Trajectory gt;
  Trajectory est;
  StillAndMoving(12, gt, est);
  // 0.3 m, 6 degrees and 3 frames all mean 3 steps here; 3 s too.
  for (const auto& [delta, unit] : {std::pair{0.3, DeltaUnit::kMeters}, {6.0, DeltaUnit::kDegrees},
                                    {6.0 * std::numbers::pi / 180, DeltaUnit::kRadians},
                                    {3.0, DeltaUnit::kFrames}, {3.0, DeltaUnit::kSeconds}}) {
    const RpeResult r = ComputeRpe(gt, est, {.delta = delta, .delta_unit = unit});
    ASSERT_GE(r.pairs, 2u) << ToString(unit);
    EXPECT_EQ(r.per_pair[0].est_index_1, 3u) << ToString(unit);
    EXPECT_NEAR(r.translation.mean, 0.3, 1e-9) << ToString(unit);
  }
  const RpeResult two_frames = ComputeRpe(gt, est, {.delta = 2.0, .delta_unit = DeltaUnit::kFrames});
  EXPECT_NEAR(two_frames.translation.mean, 0.2, 1e-12);
}

TEST(RpeTest, ScaleMultipliesTheEstimatedMotion) {
  Trajectory gt;
  Trajectory est;
  StillAndMoving(5, gt, est);
  EXPECT_NEAR(ComputeRpe(gt, est, {.scale = 2.0}).translation.mean, 0.2, 1e-12);
}

TEST(RpeTest, PairsFarFromGroundTruthAreDropped) {
  Trajectory gt;
  Trajectory est;
  StillAndMoving(10, gt, est);
  // Ground truth every second except 4..8: the median step is 1 s, so estimate
  // poses more than 2 s from any ground truth (5 < t < 7) lose their pairs.
  Trajectory holey;
  for (const StampedPose& p : gt) {
    if (p.timestamp < 3.5 || p.timestamp > 8.5) holey.push_back(p);
  }
  Trajectory dense_est;
  for (int k = 0; k < 40; ++k) dense_est.emplace_back(k * 0.25, SE3d());
  const RpeResult r = ComputeRpe(holey, dense_est);
  for (const RpePair& p : r.per_pair) {
    EXPECT_LE(std::abs(p.gt_timestamp_0 - p.est_timestamp_0), 2.0);
    EXPECT_LE(std::abs(p.gt_timestamp_1 - p.est_timestamp_1), 2.0);
  }
  EXPECT_GE(r.pairs, 2u);
  EXPECT_LT(r.pairs, 35u);  // 35 pairs (i, i + 4) without the hole
}

TEST(RpeTest, OffsetAppliesToTheEstimateClock) {
  Trajectory gt;
  Trajectory est;
  StillAndMoving(8, gt, est);
  for (StampedPose& p : est) p.timestamp += 100.0;
  EXPECT_THAT(ErrorOf(gt, est), HasSubstr("no overlap in time between GT"));
  EXPECT_EQ(ComputeRpe(gt, est, {.offset = -100.0}).pairs, 6u);
}

TEST(RpeTest, RefusesBadInput) {
  Trajectory gt;
  Trajectory est;
  StillAndMoving(5, gt, est);
  EXPECT_THAT(ErrorOf(gt, Trajectory{est[0]}), HasSubstr("estimate trajectory has 1 pose(s)"));
  EXPECT_THAT(ErrorOf(Trajectory{}, est), HasSubstr("ground truth trajectory has 0 pose(s)"));
  EXPECT_THAT(ErrorOf(gt, est, {.delta = 0.0}), HasSubstr("delta must be > 0"));
  EXPECT_THAT(ErrorOf(gt, est, {.scale = 0.0}), HasSubstr("scale must be > 0"));
  EXPECT_THAT(ErrorOf(gt, est, {.delta = 100.0}), HasSubstr("only 0 pose pair(s)"));
  EXPECT_THAT(ErrorOf(gt, est, {.delta = 0.5, .delta_unit = DeltaUnit::kFrames}), HasSubstr("must be at least 1"));
  EXPECT_THROW(ParseDeltaUnit("mm"), Error);
  EXPECT_EQ(ParseDeltaUnit("deg"), DeltaUnit::kDegrees);
  EXPECT_EQ(ToString(ParseDeltaUnit("rad")), "rad");
}

}  // namespace
}  // namespace dlslam::eval

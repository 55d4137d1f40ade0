#include "dlslam/optimize/pose_optimizer.h"

#include <gtest/gtest.h>

#include <random>

#include "dlslam/util/check.h"
#include "tests/support/numeric_diff.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// A camera looking at random points 1-5 m away; a fraction of observations
// replaced by random pixels (wrong matches).
struct Scene {
  CameraIntrinsics camera = CameraPreset("freiburg3");
  SE3d cam_from_world;
  std::vector<PoseObservation> observations;
  std::vector<bool> is_outlier;
};

Scene MakeScene(int n, double outlier_fraction, double pixel_noise, unsigned seed) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  std::normal_distribution<double> noise(0, pixel_noise);
  Vector6d xi;
  xi << 0.3, -0.1, 0.5, 0.2, -0.3, 0.1;
  s.cam_from_world = SE3d::Exp(xi);
  const SE3d world_from_cam = s.cam_from_world.Inverse();
  for (int i = 0; i < n; ++i) {
    const double z = 1 + 4 * uni(rng);
    const Eigen::Vector2d px(uni(rng) * 640, uni(rng) * 480);
    PoseObservation o;
    o.point_world = world_from_cam * s.camera.Unproject(px, z);
    const int octave = static_cast<int>(uni(rng) * 4);
    const double sigma = std::pow(1.2, octave);
    o.information = 1.0 / (sigma * sigma);
    o.pixel = px + Eigen::Vector2d(noise(rng), noise(rng)) * sigma;
    const bool with_depth = uni(rng) < 0.8;
    o.right_u = with_depth ? o.pixel.x() - s.camera.bf / z + noise(rng) * sigma : -1.0;
    const bool outlier = uni(rng) < outlier_fraction;
    if (outlier) o.pixel = Eigen::Vector2d(uni(rng) * 640, uni(rng) * 480);
    if (outlier && with_depth) o.right_u = o.pixel.x() - s.camera.bf / z;
    s.observations.push_back(o);
    s.is_outlier.push_back(outlier);
  }
  return s;
}

SE3d Perturb(const SE3d& pose, double trans, double rot) {
  Vector6d d;
  d << trans, -trans, trans / 2, rot, rot / 2, -rot;
  return SE3d::Exp(d) * pose;
}

double TranslationError(const SE3d& a, const SE3d& b) {
  return (a.Inverse().translation() - b.Inverse().translation()).norm();
}
double RotationErrorRad(const SE3d& a, const SE3d& b) { return (a.so3().Inverse() * b.so3()).Log().norm(); }

TEST(PoseOptimizer, JacobianMatchesNumericDifferences) {
  const Scene s = MakeScene(20, 0, 0, 1);
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
  const Scene s = MakeScene(100, 0, 0, 2);
  const auto r = OptimizePose(s.camera, Perturb(s.cam_from_world, 0.1, 0.05), s.observations);
  EXPECT_LT(TranslationError(r.cam_from_world, s.cam_from_world), 1e-9);
  EXPECT_LT(RotationErrorRad(r.cam_from_world, s.cam_from_world), 1e-10);
  EXPECT_EQ(r.num_inliers, 100);
}

TEST(PoseOptimizer, RejectsWrongMatchesAndStaysAccurate) {
  const Scene s = MakeScene(300, 0.3, 1.0, 3);
  const auto r = OptimizePose(s.camera, Perturb(s.cam_from_world, 0.05, 0.03), s.observations);
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
  const Scene s = MakeScene(2, 0, 0, 4);
  const SE3d start = Perturb(s.cam_from_world, 0.1, 0.1);
  const auto r = OptimizePose(s.camera, start, s.observations);
  EXPECT_EQ(r.cam_from_world.matrix(), start.matrix());
  EXPECT_EQ(r.num_inliers, 0);
}

TEST(PoseOptimizer, PointsBehindTheCameraAreOutliers) {
  Scene s = MakeScene(50, 0, 0, 5);
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

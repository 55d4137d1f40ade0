#include "dlslam/optimize/depth_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "dlslam/util/check.h"

namespace dlslam {
namespace {

// A box-shaped room (floor, ceiling, four walls, a desk block) seen by a
// camera, ray-cast analytically; optionally a "person" (an axis-aligned box)
// standing in front of the camera.
struct Box {
  Eigen::Vector3d lo, hi;
};

double RayBoxExit(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& b) {
  // Distance to the far side of the box (the room is seen from inside).
  double t_far = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) continue;
    const double t = ((d[k] > 0 ? b.hi[k] : b.lo[k]) - o[k]) / d[k];
    t_far = std::min(t_far, t);
  }
  return t_far;
}

double RayBoxEntry(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& b) {
  double t_near = -std::numeric_limits<double>::infinity(), t_far = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < b.lo[k] || o[k] > b.hi[k]) return -1;
      continue;
    }
    double t1 = (b.lo[k] - o[k]) / d[k], t2 = (b.hi[k] - o[k]) / d[k];
    if (t1 > t2) std::swap(t1, t2);
    t_near = std::max(t_near, t1);
    t_far = std::min(t_far, t2);
  }
  return t_near <= t_far && t_near > 0 ? t_near : -1;
}

CameraIntrinsics TestCamera() {
  CameraIntrinsics c;
  c.fx = c.fy = 540;
  c.cx = 319.5;
  c.cy = 239.5;
  return c;
}

// Depth [m] along the optical axis of world_from_cam's camera.
cv::Mat Render(const CameraIntrinsics& camera, const SE3d& world_from_cam, const std::vector<Box>& solids,
               double noise_per_m2 = 0.0, unsigned seed = 1) {
  const Box room{{-2.5, -1.2, -1.0}, {2.5, 1.5, 4.0}};
  std::mt19937 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  cv::Mat depth(camera.height, camera.width, CV_32FC1);
  const Eigen::Matrix3d r = world_from_cam.rotationMatrix();
  const Eigen::Vector3d o = world_from_cam.translation();
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray_cam((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
      const Eigen::Vector3d d = r * ray_cam;
      double t = RayBoxExit(o, d, room);
      for (const Box& s : solids) {
        const double ts = RayBoxEntry(o, d, s);
        if (ts > 0) t = std::min(t, ts);
      }
      const double z = t;  // ray_cam has z = 1: t is the depth
      depth.at<float>(v, u) = static_cast<float>(z + noise_per_m2 * z * z * unit(rng));
    }
  }
  return depth;
}

const std::vector<Box> kFurniture = {{{-1.5, 0.7, 2.0}, {0.2, 1.5, 3.2}}, {{1.0, -0.2, 2.5}, {1.8, 1.5, 3.5}}};

double TranslationError(const SE3d& a, const SE3d& b) { return (a.Inverse() * b).translation().norm(); }
double RotationErrorDeg(const SE3d& a, const SE3d& b) {
  return (a.Inverse() * b).so3().Log().norm() * 180.0 / 3.14159265358979323846;
}

TEST(DepthAlignmentTest, RecoversTheMotionOfAStaticRoom) {
  const CameraIntrinsics camera = TestCamera();
  const SE3d world_from_reference = SE3d::Identity();
  const SE3d world_from_current =
      SE3d(SO3d::Exp(Eigen::Vector3d(0.01, -0.03, 0.015)), Eigen::Vector3d(0.04, -0.02, 0.03));
  const cv::Mat reference = Render(camera, world_from_reference, kFurniture);
  const cv::Mat current = Render(camera, world_from_current, kFurniture);
  const SE3d truth = world_from_current.Inverse() * world_from_reference;  // current_from_reference
  const DepthAligner aligner(camera);
  const DepthAlignment a = aligner.Align(reference, current, SE3d::Identity());
  ASSERT_TRUE(a.converged);
  EXPECT_LT(TranslationError(a.current_from_reference, truth), 2e-3);
  EXPECT_LT(RotationErrorDeg(a.current_from_reference, truth), 0.1);
  EXPECT_GT(a.inlier_fraction, 0.9);
}

TEST(DepthAlignmentTest, APersonCoveringAThirdOfTheViewIsAnOutlier) {
  const CameraIntrinsics camera = TestCamera();
  const SE3d world_from_current = SE3d(SO3d::Exp(Eigen::Vector3d(0.0, 0.02, 0.0)), Eigen::Vector3d(0.03, 0, 0.02));
  // The person walks across the view (1.2 m/s) at 1.3 m and covers about a
  // third of it.
  std::vector<Box> before = kFurniture, after = kFurniture;
  before.push_back({{-0.45, -0.9, 1.3}, {0.15, 1.5, 1.6}});
  after.push_back({{-0.41, -0.9, 1.3}, {0.19, 1.5, 1.6}});
  const cv::Mat reference = Render(camera, SE3d::Identity(), before, 1.4e-3, 1);
  const cv::Mat current = Render(camera, world_from_current, after, 1.4e-3, 2);
  const SE3d truth = world_from_current.Inverse();
  const DepthAligner aligner(camera);
  const DepthAlignment a = aligner.Align(reference, current, SE3d::Identity());
  ASSERT_TRUE(a.converged);
  EXPECT_LT(TranslationError(a.current_from_reference, truth), 0.01);
  EXPECT_LT(RotationErrorDeg(a.current_from_reference, truth), 0.3);
  // The true motion explains more of the depth than "the camera followed the person".
  const DepthAlignment followed = aligner.Score(reference, current, SE3d::Identity());
  EXPECT_GT(a.inlier_fraction, followed.inlier_fraction);
}

TEST(DepthAlignmentTest, HandlesDistortionAndMissingDepth) {
  CameraIntrinsics camera = TestCamera();
  camera.k1 = 0.04;
  camera.k2 = -0.1;
  // Rendered without distortion, but a pixel ray table with distortion
  // applies the same inverse map to both images: the motion stays the same
  // up to the small warp; mainly this checks that the path runs.
  const SE3d world_from_current = SE3d(SO3d::Exp(Eigen::Vector3d(0.0, 0.01, 0.0)), Eigen::Vector3d(0.02, 0, 0));
  cv::Mat reference = Render(TestCamera(), SE3d::Identity(), kFurniture);
  cv::Mat current = Render(TestCamera(), world_from_current, kFurniture);
  current(cv::Rect(0, 0, 320, 480)).setTo(0.0f);  // half the image without depth
  current.at<float>(100, 400) = std::numeric_limits<float>::quiet_NaN();
  const DepthAligner aligner(camera);
  const DepthAlignment a = aligner.Align(reference, current, SE3d::Identity());
  EXPECT_TRUE(a.converged);
  EXPECT_LT(TranslationError(a.current_from_reference, world_from_current.Inverse()), 0.02);
}

TEST(DepthAlignmentTest, AFlatWallIsDegenerate) {
  const CameraIntrinsics camera = TestCamera();
  const cv::Mat wall(camera.height, camera.width, CV_32FC1, cv::Scalar(2.0f));
  const DepthAligner aligner(camera);
  const DepthAlignment a = aligner.Align(wall, wall, SE3d::Identity());
  EXPECT_FALSE(a.converged);
}

TEST(DepthAlignmentTest, NoDepthIsNotConverged) {
  const CameraIntrinsics camera = TestCamera();
  const cv::Mat empty(camera.height, camera.width, CV_32FC1, cv::Scalar(0.0f));
  const DepthAlignment a = DepthAligner(camera).Align(empty, empty, SE3d::Identity());
  EXPECT_FALSE(a.converged);
  EXPECT_EQ(a.samples, 0);
}

TEST(DepthAlignmentTest, RefusesWrongImagesAndOptions) {
  const CameraIntrinsics camera = TestCamera();
  const DepthAligner aligner(camera);
  const cv::Mat good(camera.height, camera.width, CV_32FC1, cv::Scalar(1.0f));
  const cv::Mat small(10, 10, CV_32FC1, cv::Scalar(1.0f));
  const cv::Mat raw(camera.height, camera.width, CV_16UC1, cv::Scalar(5000));
  EXPECT_THROW(aligner.Align(good, small, SE3d::Identity()), Error);
  EXPECT_THROW(aligner.Align(raw, good, SE3d::Identity()), Error);
  DepthAlignmentOptions bad;
  bad.sample_step = 0;
  EXPECT_THROW(DepthAligner(camera, bad), Error);
}

}  // namespace
}  // namespace dlslam

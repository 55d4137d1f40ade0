#include "dlslam/dense/tsdf_volume.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::dense {
namespace {

CameraIntrinsics SmallCamera() {
  CameraIntrinsics camera;
  camera.width = 160;
  camera.height = 120;
  camera.fx = camera.fy = 130.0;
  camera.cx = 79.5;
  camera.cy = 59.5;
  return camera;
}

// Depth of a fronto-parallel wall at `z` [m], with a box ("person") at
// `box_z` covering columns [u0, u1) when box_z > 0.
cv::Mat WallDepth(const CameraIntrinsics& camera, float z, float box_z = 0.0f, int u0 = 60, int u1 = 100) {
  cv::Mat depth(camera.height, camera.width, CV_32FC1, cv::Scalar(z));
  if (box_z > 0) depth.colRange(u0, u1).setTo(box_z);
  return depth;
}

cv::Mat Colour(const CameraIntrinsics& camera, int b, int g, int r) {
  return cv::Mat(camera.height, camera.width, CV_8UC3, cv::Scalar(b, g, r));
}

int CountNear(const std::vector<SurfacePoint>& points, float z, float tolerance) {
  int n = 0;
  for (const SurfacePoint& p : points) n += std::abs(p.position.z() - z) < tolerance;
  return n;
}

TEST(TsdfVolume, AWallSeenTwiceIsAPlaneAtItsDepth) {
  const CameraIntrinsics camera = SmallCamera();
  TsdfVolume volume(camera);
  // Two views 10 cm apart sideways, looking at the wall z = 2 (world).
  const SE3d a = SE3d::Identity();
  const SE3d b(SO3d(), Eigen::Vector3d(-0.1, 0.0, 0.0));  // cam_from_world: the camera at x = +0.1
  volume.Integrate(a, WallDepth(camera, 2.0f), Colour(camera, 10, 20, 30));
  volume.Integrate(b, WallDepth(camera, 2.0f), Colour(camera, 10, 20, 30));
  const std::vector<SurfacePoint> points = volume.ExtractSurface();
  ASSERT_GT(points.size(), 1000u);
  for (const SurfacePoint& p : points) {
    ASSERT_NEAR(p.position.z(), 2.0f, 0.2f * static_cast<float>(volume.options().voxel_size));
    EXPECT_EQ(p.bgr[0], 10);
    EXPECT_EQ(p.bgr[2], 30);
    EXPECT_EQ(p.tagged_share, 0.0f);
  }
  // The wall's footprint, 2 m x (160 / 130) wide: about one point per voxel.
  const double width = 2.0 * 160 / 130, height = 2.0 * 120 / 130, voxel = volume.options().voxel_size;
  EXPECT_GT(static_cast<double>(points.size()), 0.7 * width * height / (voxel * voxel));
  EXPECT_LT(static_cast<double>(points.size()), 1.3 * width * height / (voxel * voxel));
}

TEST(TsdfVolume, ASingleViewIsNotYetSurface) {
  const CameraIntrinsics camera = SmallCamera();
  TsdfVolume volume(camera);  // min_weight 2
  volume.Integrate(SE3d::Identity(), WallDepth(camera, 2.0f), cv::Mat());
  EXPECT_TRUE(volume.ExtractSurface().empty());
  EXPECT_GT(volume.NumBlocks(), 0u);
}

TEST(TsdfVolume, ExcludedPixelsAreNeverFused) {
  const CameraIntrinsics camera = SmallCamera();
  TsdfVolume volume(camera);
  cv::Mat person(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
  person.colRange(60, 100).setTo(255);
  for (int i = 0; i < 3; ++i) volume.Integrate(SE3d::Identity(), WallDepth(camera, 2.0f, 1.0f), cv::Mat(), person);
  const std::vector<SurfacePoint> points = volume.ExtractSurface();
  EXPECT_EQ(CountNear(points, 1.0f, 0.1f), 0);
  EXPECT_GT(CountNear(points, 2.0f, 0.02f), 1000);
  // Without the exclusion the box is in the model.
  TsdfVolume all(camera);
  for (int i = 0; i < 3; ++i) all.Integrate(SE3d::Identity(), WallDepth(camera, 2.0f, 1.0f), cv::Mat());
  EXPECT_GT(CountNear(all.ExtractSurface(), 1.0f, 0.02f), 200);
}

// A mover the masks missed in two views is carved away by the views that
// later see the free space where it stood.
TEST(TsdfVolume, LaterViewsCarveAMoverAway) {
  const CameraIntrinsics camera = SmallCamera();
  TsdfVolume volume(camera);
  cv::Mat tag(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
  tag.colRange(60, 100).setTo(255);
  for (int i = 0; i < 2; ++i) volume.Integrate(SE3d::Identity(), WallDepth(camera, 2.0f, 1.0f), cv::Mat(), {}, tag);
  std::vector<SurfacePoint> points = volume.ExtractSurface();
  const int box_points = CountNear(points, 1.0f, 0.02f);
  ASSERT_GT(box_points, 200);
  for (const SurfacePoint& p : points) {
    if (std::abs(p.position.z() - 1.0f) < 0.02f) {
      EXPECT_NEAR(p.tagged_share, 1.0f, 1e-6);
    }
  }
  for (int i = 0; i < 3; ++i) volume.Integrate(SE3d::Identity(), WallDepth(camera, 2.0f), cv::Mat());
  points = volume.ExtractSurface();
  EXPECT_EQ(CountNear(points, 1.0f, 0.1f), 0);
  // The wall behind it appears once seen often enough.
  EXPECT_GT(CountNear(points, 2.0f, 0.02f), 1000);
}

TEST(TsdfVolume, RefusesImagesOfTheWrongTypeOrSize) {
  const CameraIntrinsics camera = SmallCamera();
  TsdfVolume volume(camera);
  const cv::Mat depth = WallDepth(camera, 2.0f);
  cv::Mat depth16;
  depth.convertTo(depth16, CV_16UC1);
  EXPECT_THROW(volume.Integrate(SE3d::Identity(), depth16, cv::Mat()), Error);
  EXPECT_THROW(volume.Integrate(SE3d::Identity(), depth(cv::Rect(0, 0, 80, 60)).clone(), cv::Mat()), Error);
  EXPECT_THROW(volume.Integrate(SE3d::Identity(), depth, cv::Mat(camera.height, camera.width, CV_8UC1)), Error);
  EXPECT_THROW(volume.Integrate(SE3d::Identity(), depth, cv::Mat(), cv::Mat(10, 10, CV_8UC1)), Error);
  TsdfOptions bad;
  bad.truncation = 0.001;  // below one voxel
  EXPECT_THROW(TsdfVolume(camera, bad), Error);
}

}  // namespace
}  // namespace dlslam::dense

#include "dlslam/features/undistort.h"

#include <gtest/gtest.h>

#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

TEST(UndistortKeypointsTest, WithoutDistortionNothingMoves) {
  const std::vector<cv::KeyPoint> in = {cv::KeyPoint(10.5f, 20.25f, 31.0f, 45.0f, 12.0f, 2)};
  const std::vector<cv::KeyPoint> out = UndistortKeypoints(in, CameraPreset("fr3"));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].pt, in[0].pt);
}

TEST(UndistortKeypointsTest, InvertsTheCameraDistortionModel) {
  const CameraIntrinsics camera = CameraPreset("fr1");  // strong Kinect distortion
  std::vector<cv::KeyPoint> distorted;
  std::vector<cv::Point2d> ideal;
  for (double v = 20; v < 480; v += 55) {
    for (double u = 20; u < 640; u += 70) {
      ideal.emplace_back(u, v);
      const Eigen::Vector2d xn((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy);
      const Eigen::Vector2d xd = camera.Distort(xn);
      distorted.emplace_back(static_cast<float>(camera.fx * xd.x() + camera.cx),
                             static_cast<float>(camera.fy * xd.y() + camera.cy), 37.2f, 123.0f,
                             9.0f, 1, 5);
    }
  }
  const std::vector<cv::KeyPoint> out = UndistortKeypoints(distorted, camera);
  ASSERT_EQ(out.size(), ideal.size());
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_NEAR(out[i].pt.x, ideal[i].x, 0.02) << i;
    EXPECT_NEAR(out[i].pt.y, ideal[i].y, 0.02) << i;
    EXPECT_EQ(out[i].angle, 123.0f);
    EXPECT_EQ(out[i].octave, 1);
    EXPECT_EQ(out[i].class_id, 5);
  }
}

TEST(UndistortKeypointsTest, RejectsInvalidIntrinsics) {
  CameraIntrinsics camera = CameraPreset("fr1");
  camera.fx = 0;
  EXPECT_THROW(UndistortKeypoints({cv::KeyPoint(1, 1, 31)}, camera), Error);
}

}  // namespace
}  // namespace dlslam::features

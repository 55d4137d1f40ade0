#include "dlslam/dynamic/mask_warp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

CameraIntrinsics Camera() {
  CameraIntrinsics c = CameraPreset("fr3");
  return c;
}

// A person-sized rectangle on a fronto-parallel plane at 2 m.
struct Scene {
  cv::Mat mask = cv::Mat::zeros(480, 640, CV_8UC1);
  cv::Mat depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
  cv::Rect person{250, 120, 100, 240};
  Scene() { mask(person).setTo(255); }
};

cv::Rect Bounds(const cv::Mat& mask) { return cv::boundingRect(mask); }

TEST(MaskWarp, NoMotionKeepsTheMask) {
  const Scene scene;
  const MaskWarper warper(Camera());
  const cv::Mat same = warper.Warp(scene.mask, scene.depth, SE3d(), 0);
  const cv::Rect b = Bounds(same);
  EXPECT_NEAR(b.x, scene.person.x, 2);
  EXPECT_NEAR(b.y, scene.person.y, 2);
  EXPECT_NEAR(b.width, scene.person.width, 3);
  EXPECT_NEAR(b.height, scene.person.height, 3);
  // Filled, not a dotted grid: the closing joins the samples.
  EXPECT_GT(cv::countNonZero(same(scene.person)), 0.97 * scene.person.area());
}

TEST(MaskWarp, CameraMotionShiftsTheMaskByTheParallax) {
  const Scene scene;
  const CameraIntrinsics camera = Camera();
  const MaskWarper warper(camera);
  // The camera moves 10 cm to the right: points move left by fx * 0.1 / 2 px.
  const SE3d t_from_s(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.1, 0, 0));
  const cv::Rect b = Bounds(warper.Warp(scene.mask, scene.depth, t_from_s, 0));
  const double shift = camera.fx * 0.1 / 2.0;
  EXPECT_NEAR(b.x, scene.person.x - shift, 2);
  EXPECT_NEAR(b.width, scene.person.width, 3);
  // Nearer depth, larger parallax: the same motion at 1 m moves twice as far.
  Scene near;
  near.depth.setTo(1.0f);
  EXPECT_NEAR(Bounds(warper.Warp(near.mask, near.depth, t_from_s, 0)).x, near.person.x - 2 * shift, 2);
}

TEST(MaskWarp, PixelsWithoutDepthMoveWithTheMedianAndGrowthWidens) {
  Scene scene;
  scene.depth(cv::Rect(250, 120, 50, 240)).setTo(0.0f);  // half the person without depth
  const CameraIntrinsics camera = Camera();
  const MaskWarper warper(camera);
  const SE3d t_from_s(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.1, 0, 0));
  const cv::Rect b = Bounds(warper.Warp(scene.mask, scene.depth, t_from_s, 0));
  EXPECT_NEAR(b.x, scene.person.x - camera.fx * 0.1 / 2.0, 2);
  EXPECT_NEAR(b.width, scene.person.width, 3);
  const cv::Rect grown = Bounds(warper.Warp(scene.mask, scene.depth, t_from_s, 8));
  EXPECT_NEAR(grown.width, scene.person.width + 16, 3);
  // No depth at all: the mask stays, grown.
  EXPECT_NEAR(Bounds(warper.Warp(scene.mask, cv::Mat(), t_from_s, 0)).x, scene.person.x, 2);
}

TEST(MaskWarp, WrongInputsAreErrors) {
  const MaskWarper warper(Camera());
  EXPECT_THROW(warper.Warp(cv::Mat::zeros(10, 10, CV_8UC1), cv::Mat(), SE3d(), 0), Error);
  EXPECT_THROW(warper.Warp(cv::Mat::zeros(480, 640, CV_8UC1), cv::Mat::zeros(480, 640, CV_16UC1), SE3d(), 0), Error);
  EXPECT_THROW(MaskWarper(Camera(), MaskWarpOptions{.sample_step_px = 0}), Error);
}

}  // namespace
}  // namespace dlslam::dynamic

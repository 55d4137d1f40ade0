#include "dlslam/dynamic/mask_warp.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// The outline is exact to a cell (4 px by default).
constexpr int kCell = MaskWarpOptions{}.cell_px;

TEST(MaskWarp, NoMotionKeepsTheMaskToACell) {
  const Scene scene;
  for (const int cell : {1, 3, kCell}) {
    const MaskWarper warper(Camera(), MaskWarpOptions{.cell_px = cell});
    const cv::Mat same = warper.Warp(scene.mask, scene.depth, SE3d(), 0);
    ASSERT_EQ(same.size(), scene.mask.size());
    const cv::Rect b = Bounds(same);
    const int tolerance = std::max(1, cell);
    EXPECT_NEAR(b.x, scene.person.x, tolerance) << "cell " << cell;
    EXPECT_NEAR(b.y, scene.person.y, tolerance) << "cell " << cell;
    EXPECT_NEAR(b.width, scene.person.width, tolerance) << "cell " << cell;
    EXPECT_NEAR(b.height, scene.person.height, tolerance) << "cell " << cell;
    // Filled, not a dotted grid, and never smaller than the mask.
    EXPECT_EQ(cv::countNonZero(same(scene.person)), scene.person.area()) << "cell " << cell;
  }
}

TEST(MaskWarp, CameraMotionShiftsTheMaskByTheParallax) {
  const Scene scene;
  const CameraIntrinsics camera = Camera();
  const MaskWarper warper(camera);
  // The camera moves 10 cm to the right: points move left by fx * 0.1 / 2 px.
  const SE3d t_from_s(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.1, 0, 0));
  const cv::Rect b = Bounds(warper.Warp(scene.mask, scene.depth, t_from_s, 0));
  const double shift = camera.fx * 0.1 / 2.0;
  EXPECT_NEAR(b.x, scene.person.x - shift, kCell);
  EXPECT_NEAR(b.width, scene.person.width, kCell);
  // Nearer depth, larger parallax: the same motion at 1 m moves twice as far.
  Scene near;
  near.depth.setTo(1.0f);
  EXPECT_NEAR(Bounds(warper.Warp(near.mask, near.depth, t_from_s, 0)).x, near.person.x - 2 * shift, kCell);
}

TEST(MaskWarp, PixelsWithoutDepthMoveWithTheMedianAndGrowthWidens) {
  Scene scene;
  scene.depth(cv::Rect(250, 120, 50, 240)).setTo(0.0f);  // half the person without depth
  const CameraIntrinsics camera = Camera();
  const MaskWarper warper(camera);
  const SE3d t_from_s(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.1, 0, 0));
  const cv::Rect b = Bounds(warper.Warp(scene.mask, scene.depth, t_from_s, 0));
  EXPECT_NEAR(b.x, scene.person.x - camera.fx * 0.1 / 2.0, kCell);
  EXPECT_NEAR(b.width, scene.person.width, kCell);
  const cv::Rect grown = Bounds(warper.Warp(scene.mask, scene.depth, t_from_s, 8));
  EXPECT_NEAR(grown.width, scene.person.width + 16, kCell);
  // Growth is rounded up to whole cells: 1 px grows by a cell.
  EXPECT_GE(Bounds(warper.Warp(scene.mask, scene.depth, t_from_s, 1)).width, b.width + 2);
  // No depth at all: the mask stays, grown.
  EXPECT_NEAR(Bounds(warper.Warp(scene.mask, cv::Mat(), t_from_s, 0)).x, scene.person.x, kCell);
}

TEST(MaskWarp, WrongInputsAreErrors) {
  const MaskWarper warper(Camera());
  EXPECT_THROW(warper.Warp(cv::Mat::zeros(10, 10, CV_8UC1), cv::Mat(), SE3d(), 0), Error);
  EXPECT_THROW(warper.Warp(cv::Mat::zeros(480, 640, CV_8UC1), cv::Mat::zeros(480, 640, CV_16UC1), SE3d(), 0), Error);
  EXPECT_THROW(MaskWarper(Camera(), MaskWarpOptions{.cell_px = 0}), Error);
  EXPECT_THROW(MaskWarper(Camera(), MaskWarpOptions{.close_px = -1}), Error);
}

}  // namespace
}  // namespace dlslam::dynamic

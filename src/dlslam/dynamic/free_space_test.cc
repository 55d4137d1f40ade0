#include "dlslam/dynamic/free_space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

CameraIntrinsics Camera() { return CameraPreset("fr3"); }

// A camera looking down +z (world axes) from `centre`.
SE3d CamFromWorld(const Eigen::Vector3d& centre) {
  return SE3d(Eigen::Quaterniond::Identity(), -centre);
}

// A wall at z = 3 m, and optionally a 0.4 m square box face at z = 1.5 m
// centred on (box_x, 0): the depth a camera at `centre` sees.
// Pixels are on the camera's distorted grid (PixelRays undistorts them).
cv::Mat Render(const CameraIntrinsics& camera, const Eigen::Vector3d& centre, bool box, double box_x = 0.0) {
  cv::Mat depth(camera.height, camera.width, CV_32FC1);
  const std::vector<Eigen::Vector2f> rays = PixelRays(camera);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector2f& ray = rays[static_cast<std::size_t>(v * camera.width + u)];
      const double xn = ray.x(), yn = ray.y();
      double z = 3.0 - centre.z();
      if (box) {
        const double zb = 1.5 - centre.z();
        const double x = centre.x() + xn * zb, y = centre.y() + yn * zb;
        if (std::abs(x - box_x) < 0.2 && std::abs(y) < 0.2) z = zb;
      }
      depth.at<float>(v, u) = static_cast<float>(z);
    }
  }
  return depth;
}

// The box's pixels in a camera at `centre`.
cv::Mat BoxPixels(const CameraIntrinsics& camera, const Eigen::Vector3d& centre, double box_x = 0.0) {
  return Render(camera, centre, true, box_x) < 2.0f;
}

TEST(FreeSpaceCheck, AStaticSceneSeenFromElsewhereViolatesNothing) {
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  const Eigen::Vector3d before(0, 0, 0), now(0.08, -0.03, 0.05);
  check.Offer(Render(camera, before, true), CamFromWorld(before));
  FreeSpaceStats stats;
  const cv::Mat moved = check.Violations(Render(camera, now, true), CamFromWorld(now), &stats);
  ASSERT_EQ(moved.size(), cv::Size(camera.width, camera.height));
  EXPECT_EQ(cv::countNonZero(moved), 0);
  EXPECT_EQ(stats.views, 1);
  EXPECT_EQ(stats.views_ignored, 0);
  EXPECT_GT(stats.cells_compared, 10000);
}

TEST(FreeSpaceCheck, ADistortedCameraProjectsThroughItsDistortion) {
  // A strong lens (k1 = 0.8: points 0.4 focal lengths off the centre
  // move 27 px outwards): a box near the image's edge, seen from
  // elsewhere, stays quiet only when the check projects through the lens (as
  // a pinhole its inner outline lands on the wall beside it: "seen
  // through", ~400 cells). A box that moved in is found as with a pinhole
  // camera.
  CameraIntrinsics camera = Camera();
  camera.k1 = 0.8;
  constexpr double kNearTheEdge = 0.8;  // [m] at 1.5 m: its inner edge 0.4 focal lengths off the centre
  // No neighbourhood: it would absorb part of the lens's shift.
  FreeSpaceCheck check(camera, FreeSpaceOptions{.neighbourhood_cells = 0});
  const Eigen::Vector3d before(0, 0, 0), now(0.06, 0.02, 0.04);
  check.Offer(Render(camera, before, true, kNearTheEdge), CamFromWorld(before));
  EXPECT_EQ(cv::countNonZero(check.Violations(Render(camera, now, true, kNearTheEdge), CamFromWorld(now))), 0);
  FreeSpaceCheck empty_room(camera);
  empty_room.Offer(Render(camera, before, false), CamFromWorld(before));
  const cv::Mat moved = empty_room.Violations(Render(camera, now, true), CamFromWorld(now));
  const cv::Mat box = BoxPixels(camera, now);
  EXPECT_GT(cv::countNonZero(moved & box), 0.9 * cv::countNonZero(box));
  EXPECT_LT(cv::countNonZero(moved & ~box), 0.1 * cv::countNonZero(box));
}

TEST(FreeSpaceCheck, WhatMovedInFrontOfAPlainWallIsFound) {
  // The case the point check cannot see: the wall has no texture, so no
  // keypoint stands behind the box.
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  const Eigen::Vector3d before(0, 0, 0), now(0.05, 0, 0);
  check.Offer(Render(camera, before, false), CamFromWorld(before));
  const cv::Mat moved = check.Violations(Render(camera, now, true), CamFromWorld(now));
  const cv::Mat box = BoxPixels(camera, now);
  const double found = cv::countNonZero(moved & box) / static_cast<double>(cv::countNonZero(box));
  EXPECT_GT(found, 0.95);
  // Outside the box: at most the cells its outline cuts.
  cv::Mat outside = moved & ~box;
  EXPECT_LT(cv::countNonZero(outside), 0.1 * cv::countNonZero(box));
}

TEST(FreeSpaceCheck, SpaceLeftBehindIsNotMovedIn) {
  // The box was there and has gone: the wall now visible lies behind where
  // the view saw the box (occluded then), not in space it saw through.
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  const Eigen::Vector3d centre(0, 0, 0);
  check.Offer(Render(camera, centre, true), CamFromWorld(centre));
  EXPECT_EQ(cv::countNonZero(check.Violations(Render(camera, centre, false), CamFromWorld(centre))), 0);
}

TEST(FreeSpaceCheck, OnlyTheLeadingPartOfAMoverIsSeenThrough) {
  // The box moved 0.2 m to the right: its new right half stands where the
  // view saw the wall, its left half where the box already was.
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  const Eigen::Vector3d centre(0, 0, 0);
  check.Offer(Render(camera, centre, true, 0.0), CamFromWorld(centre));
  const cv::Mat moved = check.Violations(Render(camera, centre, true, 0.2), CamFromWorld(centre));
  const cv::Mat leading = BoxPixels(camera, centre, 0.2) & ~BoxPixels(camera, centre, 0.0);
  const cv::Mat overlap = BoxPixels(camera, centre, 0.2) & BoxPixels(camera, centre, 0.0);
  // Less a band of neighbourhood_cells along the old outline, where the
  // nearest kept depth is the box's own (71 px of leading part, ~10 px band).
  EXPECT_GT(cv::countNonZero(moved & leading), 0.8 * cv::countNonZero(leading));
  EXPECT_LT(cv::countNonZero(moved & overlap), 0.1 * cv::countNonZero(overlap));
}

TEST(FreeSpaceCheck, APoseAFewPixelsOffStaysQuietAtDepthEdges) {
  // The current pose is 1 cm off (4 px of parallax at the box's 1.5 m, 2 px
  // at the wall): the box's edges must not read as seen through.
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  const Eigen::Vector3d centre(0, 0, 0), wrong(0.01, 0.005, 0);
  check.Offer(Render(camera, centre, true), CamFromWorld(centre));
  EXPECT_EQ(cv::countNonZero(check.Violations(Render(camera, centre, true), CamFromWorld(wrong))), 0);
}

TEST(FreeSpaceCheck, AHoleInTheViewIsUnknownNotSeenThrough) {
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  const Eigen::Vector3d centre(0, 0, 0);
  cv::Mat view = Render(camera, centre, false);
  // No depth where the box will appear (a structured-light shadow).
  view.setTo(0.0f, BoxPixels(camera, centre));
  check.Offer(view, CamFromWorld(centre));
  EXPECT_EQ(cv::countNonZero(check.Violations(Render(camera, centre, true), CamFromWorld(centre))), 0);
}

TEST(FreeSpaceCheck, AMisposedViewIsIgnored) {
  // The camera moved 0.5 m towards the wall but the pose says it stayed:
  // the whole wall would be "seen through", which is a pose error.
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  const Eigen::Vector3d centre(0, 0, 0), real(0, 0, 0.5);
  check.Offer(Render(camera, centre, false), CamFromWorld(centre));
  FreeSpaceStats stats;
  const cv::Mat moved = check.Violations(Render(camera, real, false), CamFromWorld(centre), &stats);
  EXPECT_EQ(stats.views_ignored, 1);
  EXPECT_EQ(cv::countNonZero(moved), 0);
}

TEST(FreeSpaceCheck, KeepsEveryKthFrameUpToMaxViews) {
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera, FreeSpaceOptions{.view_every_frames = 3, .max_views = 2});
  const cv::Mat depth = Render(camera, Eigen::Vector3d::Zero(), false);
  EXPECT_TRUE(check.Violations(depth, SE3d()).empty());  // no view yet
  check.Offer(depth, SE3d());  // kept (the first)
  check.Offer(depth, SE3d());
  check.Offer(depth, SE3d());
  EXPECT_EQ(check.views(), 1);
  check.Offer(depth, SE3d());  // kept (the fourth)
  check.Offer(depth, SE3d());
  check.Offer(depth, SE3d());
  check.Offer(depth, SE3d());  // kept: the first dropped
  EXPECT_EQ(check.views(), 2);
  check.Reset();
  EXPECT_EQ(check.views(), 0);
}

TEST(FreeSpaceCheck, WrongInputsAreErrors) {
  const CameraIntrinsics camera = Camera();
  FreeSpaceCheck check(camera);
  EXPECT_THROW(check.Offer(cv::Mat(480, 640, CV_16UC1, cv::Scalar(0)), SE3d()), Error);
  EXPECT_THROW(check.Offer(cv::Mat(240, 320, CV_32FC1, cv::Scalar(1)), SE3d()), Error);
  check.Offer(cv::Mat(480, 640, CV_32FC1, cv::Scalar(1)), SE3d());
  EXPECT_THROW(check.Violations(cv::Mat(), SE3d()), Error);
  EXPECT_THROW(FreeSpaceCheck(camera, FreeSpaceOptions{.cell_px = 0}), Error);
  EXPECT_THROW(FreeSpaceCheck(camera, FreeSpaceOptions{.max_violated_share = 0}), Error);
}

}  // namespace
}  // namespace dlslam::dynamic

#include "dlslam/dynamic/region_growing.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

// 160x120, f = 100: a pixel at depth z spans z / 100 m.
CameraIntrinsics SmallCamera() {
  CameraIntrinsics camera;
  camera.width = 160;
  camera.height = 120;
  camera.fx = camera.fy = 100.0;
  camera.cx = 79.5;
  camera.cy = 59.5;
  return camera;
}

// A wall at 3 m with a "person" box at 1.5 m in front of it.
cv::Mat WallWithBox(const cv::Rect& box) {
  cv::Mat depth(120, 160, CV_32FC1, cv::Scalar(3.0f));
  depth(box).setTo(1.5f);
  return depth;
}

// Full resolution, no size limits: these tests are about depth.
RegionGrowingOptions Unlimited() {
  RegionGrowingOptions options;
  options.pixel_step = 1;
  options.max_distance_from_seed_m = 0;
  options.static_distance_from_seed_m = 0;
  options.static_head_start_px = 0;
  return options;
}

cv::Mat Grow(const cv::Mat& depth, const std::vector<cv::Point2f>& seeds,
             const RegionGrowingOptions& options, const std::vector<cv::Point2f>& barriers = {}) {
  return GrowDynamicRegions(depth, SmallCamera(), seeds, barriers, options);
}

TEST(GrowDynamicRegions, StopsAtDepthDiscontinuities) {
  const cv::Rect box(40, 30, 30, 50);
  const cv::Mat mask = Grow(WallWithBox(box), {{50.3f, 40.6f}}, Unlimited());
  ASSERT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(mask), box.area());
  EXPECT_EQ(cv::countNonZero(mask(box)), box.area());
}

TEST(GrowDynamicRegions, FollowsSmoothSurfaces) {
  // A slanted box surface (1 mm per pixel) is one region.
  const cv::Rect box(40, 30, 30, 50);
  cv::Mat depth = WallWithBox(box);
  for (int v = box.y; v < box.y + box.height; ++v) {
    for (int u = box.x; u < box.x + box.width; ++u) depth.at<float>(v, u) = 1.4f + 0.001f * (u - box.x);
  }
  EXPECT_EQ(cv::countNonZero(Grow(depth, {{45, 35}}, Unlimited())), box.area());
}

TEST(GrowDynamicRegions, LeakAlongATouchingSurfaceIsBounded) {
  // A floor ramp continues from the box's depth away from the camera; the
  // fill follows it only within max_depth_from_seed_m of the seed.
  cv::Mat depth(120, 160, CV_32FC1, cv::Scalar(3.0f));
  for (int u = 0; u < 160; ++u) depth.col(u).setTo(1.0f + 0.01f * u);  // 1 cm per column
  RegionGrowingOptions options = Unlimited();
  options.max_depth_from_seed_m = 0.3;
  const cv::Mat mask = Grow(depth, {{0, 50}}, options);
  // Columns 0..30 are within 0.3 m of the seed's 1.0 m.
  EXPECT_EQ(cv::countNonZero(mask), 31 * 120);
  EXPECT_EQ(mask.at<std::uint8_t>(50, 30), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(50, 31), 0);
}

TEST(GrowDynamicRegions, SizeLimitIsMetricNotPixels) {
  // The same 0.205 m limit on a flat wall at 1 m and at 2 m: a disc of
  // radius f * 0.205 / z = 20.5 px and 10.25 px around the seed (seed at the principal
  // point, so the wall's 3-D distance is exactly z * pixel distance / f).
  RegionGrowingOptions options;
  options.pixel_step = 1;
  options.max_distance_from_seed_m = 0.205;
  for (const float z : {1.0f, 2.0f}) {
    const cv::Mat wall(120, 160, CV_32FC1, cv::Scalar(z));
    const cv::Mat mask = Grow(wall, {{79.5f, 59.5f}}, options);
    const double radius_px = 100.0 * 0.205 / z;
    int expected = 0;  // lattice points within the radius of the seed pixel (80, 60)
    for (int v = 0; v < 120; ++v) {
      for (int u = 0; u < 160; ++u) {
        const double du = (u - 79.5) * z / 100.0, dv = (v - 59.5) * z / 100.0;
        const double su = (80 - 79.5) * z / 100.0, sv = (60 - 59.5) * z / 100.0;
        expected += std::hypot(du - su, dv - sv) <= 0.205;
      }
    }
    EXPECT_EQ(cv::countNonZero(mask), expected) << "z " << z;
    EXPECT_NEAR(expected, M_PI * radius_px * radius_px, 0.1 * M_PI * radius_px * radius_px);
  }
}

TEST(GrowDynamicRegions, StaticPointsCompeteForTheSurface) {
  // One flat wall at 2 m, a dynamic seed at column 40 and a static one at
  // column 100 on the same row: the wall splits halfway, at column 70.
  const cv::Mat wall(120, 160, CV_32FC1, cv::Scalar(2.0f));
  const cv::Mat mask = Grow(wall, {{40, 60}}, Unlimited(), {{100, 60}});
  EXPECT_EQ(mask.at<std::uint8_t>(60, 69), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(60, 71), 0);
  EXPECT_EQ(mask.at<std::uint8_t>(60, 100), 0);
  // A head start of 20 px moves the split by 10 px: 40 + h = 100 - (h - 20).
  RegionGrowingOptions head_start = Unlimited();
  head_start.static_head_start_px = 20;
  const cv::Mat later = Grow(wall, {{40, 60}}, head_start, {{100, 60}});
  EXPECT_EQ(later.at<std::uint8_t>(60, 79), 255);
  EXPECT_EQ(later.at<std::uint8_t>(60, 81), 0);
  // Without the competition the whole wall is dynamic.
  RegionGrowingOptions no_barriers = Unlimited();
  no_barriers.static_points_compete = false;
  EXPECT_EQ(cv::countNonZero(Grow(wall, {{40, 60}}, no_barriers, {{100, 60}})), 160 * 120);
  // A pixel that is both keeps its dynamic evidence.
  EXPECT_EQ(Grow(wall, {{40, 60}}, Unlimited(), {{40, 60}}).at<std::uint8_t>(60, 40), 255);
}

// A person (a 0.6 x 1.7 m board at 2 m) standing on a floor 0.5 m below
// the camera, a wall at 4 m; 640x480, f = 525. The feet touch the floor, so
// the depth is continuous from the legs onto the floor in front of them.
struct PersonOnFloor {
  CameraIntrinsics camera;  // 640x480 default
  cv::Mat depth = cv::Mat(480, 640, CV_32FC1);
  cv::Mat person = cv::Mat::zeros(480, 640, CV_8UC1);
  std::vector<cv::Point2f> person_points, scene_points;  // keypoint-like grids
  int contact_row = 0;                                    // the feet's lowest row

  PersonOnFloor() {
    for (int v = 0; v < 480; ++v) {
      for (int u = 0; u < 640; ++u) {
        const double rx = (u - camera.cx) / camera.fx, ry = (v - camera.cy) / camera.fy;
        double z = 4.0;                                       // wall
        if (ry > 0 && 0.5 / ry < z) z = 0.5 / ry;             // floor y = 0.5
        const double x2 = rx * 2.0, y2 = ry * 2.0;             // the board's plane z = 2
        if (std::abs(x2) <= 0.3 && y2 >= -1.2 && y2 <= 0.5 && z > 2.0) {
          z = 2.0;
          person.at<std::uint8_t>(v, u) = 255;
          contact_row = std::max(contact_row, v);
        }
        depth.at<float>(v, u) = static_cast<float>(z);
      }
    }
    // Dynamic points on the person, static ones on floor and wall, every 24 px.
    for (int v = 4; v < 480; v += 24) {
      for (int u = 4; u < 640; u += 24) {
        (person.at<std::uint8_t>(v, u) ? person_points : scene_points).emplace_back(u, v);
      }
    }
  }
};

TEST(GrowDynamicRegions, PersonOnTheFloorDoesNotLeakOntoIt) {
  const PersonOnFloor scene;
  ASSERT_GT(scene.contact_row, 300);
  ASSERT_LT(scene.contact_row, 470);
  ASSERT_GT(scene.person_points.size(), 50u);
  const RegionGrowingOptions options;  // defaults: static points compete, 0.45 m
  const cv::Mat mask =
      GrowDynamicRegions(scene.depth, scene.camera, scene.person_points, scene.scene_points, options);
  const int person_pixels = cv::countNonZero(scene.person);
  const int covered = cv::countNonZero(mask & scene.person);
  EXPECT_GT(covered, 0.97 * person_pixels);
  // Outside the person: only floor at the feet, within the head start
  // (20 px) plus half the static grid's spacing (12 px) plus slack of the
  // contact line (the person's bottom row).
  // (The 2-px grid may add a 1-px band along the outline.)
  cv::Mat person_and_outline;
  cv::dilate(scene.person, person_and_outline, cv::Mat::ones(3, 3, CV_8UC1));
  cv::Mat outside = mask & ~person_and_outline;
  int first_col = 640, last_col = 0;
  for (int u = 0; u < 640; ++u) {
    if (scene.person.at<std::uint8_t>(scene.contact_row, u)) {
      first_col = std::min(first_col, u);
      last_col = std::max(last_col, u);
    }
  }
  double farthest = 0;
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      if (!outside.at<std::uint8_t>(v, u)) continue;
      const int du = u < first_col ? first_col - u : (u > last_col ? u - last_col : 0);
      farthest = std::max(farthest, std::hypot(du, v - scene.contact_row));
    }
  }
  EXPECT_LE(farthest, 36.0);
  EXPECT_LT(cv::countNonZero(outside), (last_col - first_col + 1 + 2 * 36) * 36);
  // The 1-D reference without static points: the fill runs along the floor
  // until max_depth_from_seed_m or the metric limit stops it.
  RegionGrowingOptions no_barriers;
  no_barriers.static_points_compete = false;
  const cv::Mat leaky =
      GrowDynamicRegions(scene.depth, scene.camera, scene.person_points, scene.scene_points, no_barriers);
  EXPECT_GT(cv::countNonZero(leaky & ~scene.person), 2 * cv::countNonZero(outside));
}

TEST(GrowDynamicRegions, CoarseGridMatchesFullResolution) {
  // An odd-placed box: the 2-px grid's region differs from the exact one
  // only along the outline (a 1-px band).
  const cv::Rect box(41, 31, 31, 47);
  RegionGrowingOptions coarse = Unlimited();
  coarse.pixel_step = 2;
  const cv::Mat exact = Grow(WallWithBox(box), {{50, 40}}, Unlimited());
  const cv::Mat fast = Grow(WallWithBox(box), {{50, 40}}, coarse);
  ASSERT_EQ(fast.size(), exact.size());
  const cv::Rect inner(box.x + 1, box.y + 1, box.width - 2, box.height - 2);
  const cv::Rect outer(box.x - 1, box.y - 1, box.width + 2, box.height + 2);
  EXPECT_EQ(cv::countNonZero(fast(inner)), inner.area());
  EXPECT_EQ(cv::countNonZero(fast), cv::countNonZero(fast(outer)));
}

TEST(GrowDynamicRegions, RegionSizeIsCapped) {
  RegionGrowingOptions options;
  options.pixel_step = 1;
  options.max_region_pixels = 500;
  const cv::Mat mask = Grow(WallWithBox({40, 30, 30, 50}), {{50, 40}}, options);
  EXPECT_EQ(cv::countNonZero(mask), 500);
  EXPECT_EQ(mask.at<std::uint8_t>(40, 50), 255);  // grown around the seed
}

TEST(GrowDynamicRegions, HolesBlockAndBadSeedsAreIgnored) {
  cv::Mat depth = WallWithBox({40, 30, 30, 50});
  depth.col(55).setTo(0.0f);  // a column of holes cuts the box in two
  const cv::Mat mask = Grow(depth, {{50, 40}, {55, 40}, {-3, 5}, {500, 5}}, Unlimited());
  EXPECT_EQ(cv::countNonZero(mask), 15 * 50);  // columns 40..54
  EXPECT_EQ(cv::countNonZero(Grow(depth, {}, {}, {{50, 40}})), 0);
}

TEST(GrowDynamicRegions, RejectsWrongTypeOrSize) {
  EXPECT_THROW(Grow(cv::Mat(120, 160, CV_16UC1), {{1, 1}}, {}), Error);
  EXPECT_THROW(Grow(cv::Mat(100, 160, CV_32FC1, cv::Scalar(1.0f)), {{1, 1}}, {}), Error);
}

TEST(RegionGrowingOptions, CheckRejectsBadValues) {
  EXPECT_NO_THROW(RegionGrowingOptions{}.Check());
  auto bad = [](auto mutate) {
    RegionGrowingOptions o;
    mutate(o);
    return o;
  };
  EXPECT_THROW(bad([](auto& o) { o.max_step_m = -0.1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_step_relative = 2; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_depth_from_seed_m = 0; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_region_pixels = 0; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_distance_from_seed_m = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.static_distance_from_seed_m = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.pixel_step = 3; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.static_head_start_px = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_depth_m = 0.05; }).Check(), Error);
}

}  // namespace
}  // namespace dlslam::dynamic

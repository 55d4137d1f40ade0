#include "dlslam/dynamic/region_growing.h"

#include <gtest/gtest.h>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

// A wall at 3 m with a "person" box at 1.5 m in front of it.
cv::Mat WallWithBox(const cv::Rect& box) {
  cv::Mat depth(120, 160, CV_32FC1, cv::Scalar(3.0f));
  depth(box).setTo(1.5f);
  return depth;
}

// No image-distance limit: these tests are about depth.
RegionGrowingOptions Unlimited() {
  RegionGrowingOptions options;
  options.max_distance_from_seed_px = 0;
  return options;
}

TEST(GrowDynamicRegions, StopsAtDepthDiscontinuities) {
  const cv::Rect box(40, 30, 30, 50);
  const cv::Mat mask = GrowDynamicRegions(WallWithBox(box), {{50.3f, 40.6f}}, Unlimited());
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
  EXPECT_EQ(cv::countNonZero(GrowDynamicRegions(depth, {{45, 35}}, Unlimited())), box.area());
}

TEST(GrowDynamicRegions, LeakAlongATouchingSurfaceIsBounded) {
  // A floor ramp continues from the box's depth away from the camera; the
  // fill follows it only within max_depth_from_seed_m of the seed.
  cv::Mat depth(100, 200, CV_32FC1, cv::Scalar(3.0f));
  for (int u = 0; u < 200; ++u) depth.col(u).setTo(1.0f + 0.01f * u);  // 1 cm per column
  RegionGrowingOptions options = Unlimited();
  options.max_depth_from_seed_m = 0.3;
  const cv::Mat mask = GrowDynamicRegions(depth, {{0, 50}}, options);
  // Columns 0..30 are within 0.3 m of the seed's 1.0 m.
  EXPECT_EQ(cv::countNonZero(mask), 31 * 100);
  EXPECT_EQ(mask.at<std::uint8_t>(50, 30), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(50, 31), 0);
}

TEST(GrowDynamicRegions, ImageDistanceFromSeedIsLimited) {
  RegionGrowingOptions options;
  options.max_distance_from_seed_px = 10;
  const cv::Mat mask = GrowDynamicRegions(WallWithBox({20, 20, 100, 80}), {{60, 60}}, options);
  // A disc of radius 10 (4-connected fill of the lattice disc: 317 pixels).
  int disc = 0;
  for (int dv = -10; dv <= 10; ++dv) {
    for (int du = -10; du <= 10; ++du) disc += du * du + dv * dv <= 100;
  }
  EXPECT_EQ(cv::countNonZero(mask), disc);
  EXPECT_EQ(mask.at<std::uint8_t>(60, 70), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(60, 71), 0);
  // A second seed grows its own disc; one inside the first region is skipped.
  const cv::Mat two = GrowDynamicRegions(WallWithBox({20, 20, 100, 80}), {{40, 40}, {60, 60}, {62, 60}}, options);
  EXPECT_EQ(cv::countNonZero(two), 2 * disc - cv::countNonZero(
      GrowDynamicRegions(WallWithBox({20, 20, 100, 80}), {{40, 40}}, options) &
      GrowDynamicRegions(WallWithBox({20, 20, 100, 80}), {{60, 60}}, options)));
}

TEST(GrowDynamicRegions, RegionSizeIsCapped) {
  RegionGrowingOptions options;
  options.max_region_pixels = 500;
  const cv::Mat mask = GrowDynamicRegions(WallWithBox({40, 30, 30, 50}), {{50, 40}}, options);
  EXPECT_EQ(cv::countNonZero(mask), 500);
  EXPECT_EQ(mask.at<std::uint8_t>(40, 50), 255);  // grown around the seed
}

TEST(GrowDynamicRegions, HolesBlockAndBadSeedsAreIgnored) {
  cv::Mat depth = WallWithBox({40, 30, 30, 50});
  depth.col(55).setTo(0.0f);  // a column of holes cuts the box in two
  const cv::Mat mask =
      GrowDynamicRegions(depth, {{50, 40}, {55, 40}, {-3, 5}, {500, 5}}, Unlimited());
  EXPECT_EQ(cv::countNonZero(mask), 15 * 50);  // columns 40..54
  EXPECT_EQ(cv::countNonZero(GrowDynamicRegions(depth, {}, {})), 0);
}

TEST(GrowDynamicRegions, RejectsWrongType) {
  EXPECT_THROW(GrowDynamicRegions(cv::Mat(10, 10, CV_16UC1), {{1, 1}}, {}), Error);
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
  EXPECT_THROW(bad([](auto& o) { o.max_distance_from_seed_px = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_depth_m = 0.05; }).Check(), Error);
}

}  // namespace
}  // namespace dlslam::dynamic

#include "dlslam/dynamic/mask_completion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

constexpr double kFocal = 500.0;

// Exact pixel counts: on the full grid, reach 0.25 m, depth margin 0.2 m.
MaskCompletionOptions Exact() {
  MaskCompletionOptions options;
  options.enabled = true;
  options.reach_m = 0.25;
  options.depth_margin_m = 0.2;
  options.pixel_step = 1;
  return options;
}

// A person at 2 m (the network found the torso, rows 100-199, and missed the
// scarf beside it and the legs below a table edge at 1 m), a wall at 4 m.
// At 2 m, reach 0.25 m is 62.5 px.
struct Scene {
  cv::Mat depth = cv::Mat(320, 400, CV_32FC1, cv::Scalar(4.0f));
  cv::Mat mask = cv::Mat::zeros(320, 400, CV_8UC1);
  cv::Rect torso{150, 100, 80, 100}, scarf{230, 120, 20, 60}, table{100, 200, 200, 30}, legs{160, 230, 60, 30},
      far_legs{160, 300, 60, 20};
  Scene() {
    depth(torso).setTo(2.0f);
    depth(scarf).setTo(2.1f);
    depth(table).setTo(1.0f);
    depth(legs).setTo(1.9f);
    depth(far_legs).setTo(2.0f);  // 100 px below the torso: out of reach
    mask(torso).setTo(255);
  }
};

int Set(const cv::Mat& mask, const cv::Rect& r) { return cv::countNonZero(mask(r)); }

TEST(MaskCompletion, AddsThePixelsBesideAPersonAtTheirDepthAndNothingElse) {
  const Scene s;
  const cv::Mat completed = CompleteMaskByDepth(s.mask, s.depth, kFocal, Exact());
  EXPECT_EQ(Set(completed, s.torso), s.torso.area());
  EXPECT_EQ(Set(completed, s.scarf), s.scarf.area());
  // The legs below the table: 31-60 px from the torso.
  EXPECT_EQ(Set(completed, s.legs), s.legs.area());
  EXPECT_EQ(Set(completed, s.table), 0);
  EXPECT_EQ(Set(completed, s.far_legs), 0);
  EXPECT_EQ(cv::countNonZero(completed), s.torso.area() + s.scarf.area() + s.legs.area());
}

TEST(MaskCompletion, ReachIsMetricSoAFartherPersonReachesFewerPixels) {
  Scene s;
  s.depth.setTo(4.0f);
  s.depth(cv::Rect(150, 100, 160, 100)).setTo(3.0f);  // torso and 80 px to its right at 3 m
  s.depth(s.torso).setTo(3.0f);
  const cv::Mat completed = CompleteMaskByDepth(s.mask, s.depth, kFocal, Exact());
  // 0.25 m at 3 m is 41.7 px.
  EXPECT_EQ(Set(completed, cv::Rect(230, 100, 41, 100)), 41 * 100);
  EXPECT_EQ(Set(completed, cv::Rect(273, 100, 37, 100)), 0);
}

TEST(MaskCompletion, LeavesTheMaskAloneWhenOffOrWhenASegmentsDepthSaysLittle) {
  Scene s;
  MaskCompletionOptions off = Exact();
  off.enabled = false;
  EXPECT_EQ(cv::countNonZero(CompleteMaskByDepth(s.mask, s.depth, kFocal, off)), s.torso.area());

  MaskCompletionOptions large = Exact();
  large.min_segment_pixels = s.torso.area() + 1;
  EXPECT_EQ(cv::countNonZero(CompleteMaskByDepth(s.mask, s.depth, kFocal, large)), s.torso.area());

  // Most of the torso without depth (a sensor hole): no band to trust.
  s.depth(cv::Rect(150, 100, 80, 60)).setTo(0.0f);
  EXPECT_EQ(cv::countNonZero(CompleteMaskByDepth(s.mask, s.depth, kFocal, Exact())),
            s.torso.area());
}

TEST(MaskCompletion, InvalidDepthNeverJoins) {
  Scene s;
  s.depth(s.scarf).setTo(std::numeric_limits<float>::quiet_NaN());
  s.depth(s.legs).setTo(0.0f);
  const cv::Mat completed = CompleteMaskByDepth(s.mask, s.depth, kFocal, Exact());
  EXPECT_EQ(cv::countNonZero(completed), s.torso.area());
}

TEST(MaskCompletion, EachSegmentHasItsOwnBand) {
  Scene s;
  // A second person at 3.9 m on the left: the wall at 4 m beside them is in
  // their band, not in the first one's.
  const cv::Rect second{20, 100, 40, 100};
  s.mask(second).setTo(255);
  s.depth(second).setTo(3.9f);
  const cv::Mat completed = CompleteMaskByDepth(s.mask, s.depth, kFocal, Exact());
  // 0.25 m at 3.9 m: 32 px each side of the second person.
  EXPECT_EQ(Set(completed, cv::Rect(60, 100, 31, 100)), 31 * 100);
  EXPECT_EQ(Set(completed, cv::Rect(93, 100, 57, 100)), 0);
  EXPECT_EQ(Set(completed, s.table), 0);
}

TEST(MaskCompletion, TheCoarseGridAddsTheSameRegionsUpToTheirOutline) {
  const Scene s;
  MaskCompletionOptions coarse = Exact();
  coarse.pixel_step = 2;
  const cv::Mat fine = CompleteMaskByDepth(s.mask, s.depth, kFocal, Exact());
  const cv::Mat grid = CompleteMaskByDepth(s.mask, s.depth, kFocal, coarse);
  EXPECT_EQ(Set(grid, s.torso), s.torso.area());
  EXPECT_EQ(Set(grid, s.scarf), s.scarf.area());
  EXPECT_EQ(Set(grid, s.table), 0);
  EXPECT_EQ(Set(grid, s.far_legs), 0);
  // Pixels that differ: at most a 2-px band along the added regions' outline.
  const cv::Mat differ = fine != grid;
  EXPECT_LT(cv::countNonZero(differ), 2 * 2 * (s.legs.width + s.legs.height));
}

TEST(MaskCompletion, RefusesBadInputsAndOptions) {
  const Scene s;
  EXPECT_THROW(CompleteMaskByDepth(s.mask, cv::Mat(10, 10, CV_32FC1), kFocal, {}), Error);
  EXPECT_THROW(CompleteMaskByDepth(s.mask, cv::Mat(320, 400, CV_16UC1), kFocal, {}), Error);
  EXPECT_THROW(CompleteMaskByDepth(cv::Mat(320, 400, CV_32FC1), s.depth, kFocal, {}), Error);
  EXPECT_THROW(CompleteMaskByDepth(s.mask, s.depth, 0.0, {}), Error);
  MaskCompletionOptions bad;
  bad.reach_m = -1;
  EXPECT_THROW(bad.Check(), Error);
  bad = {};
  bad.min_depth_m = 5;
  bad.max_depth_m = 1;
  EXPECT_THROW(bad.Check(), Error);
  bad = {};
  bad.pixel_step = 3;
  EXPECT_THROW(bad.Check(), Error);
}

}  // namespace
}  // namespace dlslam::dynamic

#include "dlslam/image/upsample.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::image {
namespace {

// What the grid-based checks did before: OpenCV's nearest resize, cropped.
cv::Mat OpenCvUpsample(const cv::Mat& grid, int factor, cv::Size size) {
  cv::Mat full;
  cv::resize(grid, full, cv::Size(grid.cols * factor, grid.rows * factor), 0, 0, cv::INTER_NEAREST);
  return full(cv::Rect(0, 0, size.width, size.height)).clone();
}

TEST(UpsampleNearest, MatchesOpenCvsNearestResizeAndCrop) {
  cv::RNG rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int factor = rng.uniform(1, 9);
    cv::Mat grid(rng.uniform(1, 40), rng.uniform(1, 60), CV_8UC1);
    rng.fill(grid, cv::RNG::UNIFORM, 0, 256);
    const cv::Size size(grid.cols * factor - rng.uniform(0, factor), grid.rows * factor - rng.uniform(0, factor));
    const cv::Mat ours = UpsampleNearest(grid, factor, size);
    ASSERT_EQ(ours.size(), size);
    EXPECT_EQ(cv::countNonZero(ours != OpenCvUpsample(grid, factor, size)), 0)
        << grid.cols << "x" << grid.rows << " x" << factor << " to " << size.width << "x" << size.height;
  }
}

TEST(UpsampleNearest, ReadsViewsAndRefusesWhatDoesNotFit) {
  cv::Mat big(30, 40, CV_8UC1);
  cv::randu(big, 0, 256);
  const cv::Mat view = big(cv::Rect(3, 2, 20, 15));
  EXPECT_EQ(cv::countNonZero(UpsampleNearest(view, 4, {78, 60}) != OpenCvUpsample(view, 4, {78, 60})), 0);
  EXPECT_THROW(UpsampleNearest(view, 4, {81, 60}), Error);
  EXPECT_THROW(UpsampleNearest(view, 0, {10, 10}), Error);
  EXPECT_THROW(UpsampleNearest(cv::Mat::zeros(4, 4, CV_32FC1), 2, {8, 8}), Error);
}

}  // namespace
}  // namespace dlslam::image

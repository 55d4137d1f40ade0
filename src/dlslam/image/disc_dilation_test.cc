#include "dlslam/image/disc_dilation.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::image {
namespace {

cv::Mat OpenCvDisc(const cv::Mat& mask, int radius) {
  cv::Mat out;
  cv::dilate(mask, out, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)));
  return out;
}

void ExpectSame(const cv::Mat& expected, const cv::Mat& actual, const std::string& what) {
  ASSERT_EQ(actual.type(), CV_8UC1) << what;
  ASSERT_EQ(actual.size(), expected.size()) << what;
  EXPECT_EQ(cv::countNonZero(expected != actual), 0) << what;
}

TEST(DilateDisc, SinglePixelGrowsIntoOpenCvsEllipseKernel) {
  for (int radius = 0; radius <= 12; ++radius) {
    cv::Mat mask = cv::Mat::zeros(41, 41, CV_8UC1);
    mask.at<std::uint8_t>(20, 20) = 255;
    const cv::Mat grown = DilateDisc(mask, radius);
    const cv::Mat kernel =
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)) * 255;
    const cv::Rect around(20 - radius, 20 - radius, 2 * radius + 1, 2 * radius + 1);
    ExpectSame(kernel, grown(around), "radius " + std::to_string(radius));
    EXPECT_EQ(cv::countNonZero(grown), cv::countNonZero(kernel)) << "radius " << radius;
  }
}

// Random masks of awkward sizes (widths around the 16- and 64-pixel blocks,
// one row, one column) and radii, sparse and dense, against cv::dilate.
TEST(DilateDisc, MatchesCvDilateOnRandomMasks) {
  cv::RNG rng(7);
  const int widths[] = {1, 2, 7, 8, 15, 16, 17, 63, 64, 65, 127, 130, 640};
  for (int trial = 0; trial < 300; ++trial) {
    const int cols = widths[trial % (sizeof(widths) / sizeof(widths[0]))];
    const int rows = rng.uniform(1, 50);
    const int radius = rng.uniform(0, 15);
    cv::Mat noise(rows, cols, CV_8UC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
    const int keep_above = trial % 3 == 0 ? 250 : (trial % 3 == 1 ? 128 : 5);
    const cv::Mat mask = noise > keep_above;
    ExpectSame(OpenCvDisc(mask, radius), DilateDisc(mask, radius),
               std::to_string(rows) + "x" + std::to_string(cols) + " radius " + std::to_string(radius));
  }
}

TEST(DilateDisc, AnyNonZeroPixelCountsAndViewsAreRead) {
  cv::Mat big = cv::Mat::zeros(60, 90, CV_8UC1);
  big.at<std::uint8_t>(30, 40) = 1;
  big.at<std::uint8_t>(10, 70) = 77;
  const cv::Mat view = big(cv::Rect(5, 3, 80, 50));  // not continuous
  ExpectSame(OpenCvDisc(view != 0, 4), DilateDisc(view, 4), "view");
}

TEST(DilateDisc, InPlaceAndIntoAReusedBuffer) {
  cv::Mat mask = cv::Mat::zeros(48, 70, CV_8UC1);
  cv::circle(mask, cv::Point(30, 20), 6, 255, -1);
  mask.at<std::uint8_t>(47, 69) = 255;
  const cv::Mat expected = OpenCvDisc(mask, 5);
  cv::Mat reused(48, 70, CV_8UC1, cv::Scalar(9));
  DilateDisc(mask, 5, reused);
  ExpectSame(expected, reused, "into a buffer");
  DilateDisc(mask, 5, mask);
  ExpectSame(expected, mask, "in place");
}

TEST(DilateDisc, EmptyMasksAndBadInput) {
  EXPECT_TRUE(DilateDisc(cv::Mat(), 3).empty());
  EXPECT_EQ(cv::countNonZero(DilateDisc(cv::Mat::zeros(20, 30, CV_8UC1), 5)), 0);
  EXPECT_THROW(DilateDisc(cv::Mat::zeros(4, 4, CV_16UC1), 1), Error);
  EXPECT_THROW(DilateDisc(cv::Mat::zeros(4, 4, CV_8UC3), 1), Error);
  EXPECT_THROW(DilateDisc(cv::Mat::zeros(4, 4, CV_8UC1), -1), Error);
}

}  // namespace
}  // namespace dlslam::image

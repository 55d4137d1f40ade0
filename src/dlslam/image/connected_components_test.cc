#include "dlslam/image/connected_components.h"

#include <gtest/gtest.h>

#include <map>
#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::image {
namespace {

// Ours and OpenCV's labels describe the same partition: a one-to-one map
// between their labels, background to background, with the same areas.
void ExpectSameComponents(const cv::Mat& mask) {
  cv::Mat ours, theirs, stats, centroids;
  std::vector<int> areas;
  const int n = LabelComponents(mask, ours, &areas);
  const int n_cv = cv::connectedComponentsWithStats(mask, theirs, stats, centroids, 8, CV_32S);
  ASSERT_EQ(n, n_cv) << mask.cols << "x" << mask.rows;
  ASSERT_EQ(ours.type(), CV_32SC1);
  std::map<int, int> to_cv, from_cv;
  int next_new = 1;  // components numbered in the order their first pixel comes
  for (int y = 0; y < mask.rows; ++y) {
    for (int x = 0; x < mask.cols; ++x) {
      const int a = ours.at<int>(y, x), b = theirs.at<int>(y, x);
      ASSERT_EQ(a == 0, mask.at<std::uint8_t>(y, x) == 0) << x << ", " << y;
      if (a != 0 && !to_cv.count(a)) {
        ASSERT_EQ(a, next_new++) << "label order at " << x << ", " << y;
      }
      const auto [i, new_a] = to_cv.emplace(a, b);
      const auto [j, new_b] = from_cv.emplace(b, a);
      ASSERT_EQ(i->second, b) << "one of our labels is two of OpenCV's at " << x << ", " << y;
      ASSERT_EQ(j->second, a) << "one of OpenCV's labels is two of ours at " << x << ", " << y;
    }
  }
  ASSERT_EQ(areas.size(), static_cast<std::size_t>(n));
  for (const auto& [a, b] : to_cv) EXPECT_EQ(areas[static_cast<std::size_t>(a)], stats.at<int>(b, cv::CC_STAT_AREA));
}

TEST(LabelComponents, SamePartitionAndAreasAsOpenCvOnRandomMasks) {
  cv::RNG rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    cv::Mat mask(rng.uniform(1, 70), rng.uniform(1, 90), CV_8UC1);
    // Noise at several densities, and blobs with holes, diagonal contacts and long runs.
    cv::Mat noise(mask.size(), CV_32FC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
    const double density = rng.uniform(0.0, 1.0);
    mask = noise < density;
    if (trial % 3 == 0) {
      cv::Mat blobs = cv::Mat::zeros(mask.size(), CV_8UC1);
      for (int k = 0; k < 6; ++k) {
        cv::ellipse(blobs, {rng.uniform(0, mask.cols), rng.uniform(0, mask.rows)},
                    {rng.uniform(1, 20), rng.uniform(1, 20)}, rng.uniform(0, 180), 0, 360, cv::Scalar(rng.uniform(1, 256)),
                    rng.uniform(-1, 3));
      }
      mask = blobs;
    }
    ExpectSameComponents(mask);
  }
}

TEST(LabelComponents, DiagonalsConnectAndViewsAreRead) {
  cv::Mat big = cv::Mat::zeros(12, 20, CV_8UC1);
  big.at<std::uint8_t>(3, 4) = 1;
  big.at<std::uint8_t>(4, 5) = 9;  // diagonal to (4, 3): one component
  big.at<std::uint8_t>(3, 7) = 200;
  big(cv::Rect(10, 6, 8, 3)).setTo(255);
  const cv::Mat view = big(cv::Rect(2, 1, 17, 10));
  cv::Mat labels;
  std::vector<int> areas;
  EXPECT_EQ(LabelComponents(view, labels, &areas), 4);
  EXPECT_EQ(labels.at<int>(2, 2), labels.at<int>(3, 3));
  EXPECT_EQ(areas, (std::vector<int>{170 - 2 - 1 - 24, 2, 1, 24}));
  ExpectSameComponents(view);
  EXPECT_EQ(LabelComponents(cv::Mat::zeros(5, 5, CV_8UC1), labels), 1);
  EXPECT_EQ(LabelComponents(cv::Mat(0, 0, CV_8UC1), labels), 1);
  EXPECT_THROW(LabelComponents(cv::Mat::zeros(4, 4, CV_16UC1), labels), Error);
}

}  // namespace
}  // namespace dlslam::image

#include "dlslam/semantic/label_maps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dlslam/util/check.h"

namespace dlslam::semantic {
namespace {

cv::Mat RandomBlob(int classes, int height, int width, unsigned seed, bool coarse) {
  const int shape[] = {1, classes, height, width};
  cv::Mat blob(4, shape, CV_32F);
  std::mt19937 rng(seed);
  // Coarse values (a few levels) make ties frequent.
  std::uniform_int_distribution<int> level(0, 3);
  std::normal_distribution<float> fine(0.f, 3.f);
  float* data = blob.ptr<float>();
  for (std::size_t i = 0; i < blob.total(); ++i) data[i] = coarse ? static_cast<float>(level(rng)) : fine(rng);
  return blob;
}

// The obvious per-pixel loop: the reference for the vectorised version.
int NaiveArgmax(const cv::Mat& blob, int y, int x) {
  int best = 0;
  for (int c = 1; c < blob.size[1]; ++c) {
    if (blob.ptr<float>(0, c, y)[x] > blob.ptr<float>(0, best, y)[x]) best = c;
  }
  return best;
}

TEST(ArgmaxLabels, EqualsPerPixelArgmaxFirstOnTies) {
  for (const bool coarse : {false, true}) {
    for (const int classes : {1, 2, 3, 21}) {
      const cv::Mat blob = RandomBlob(classes, 17, 23, 7u + static_cast<unsigned>(classes), coarse);
      const cv::Mat labels = ArgmaxLabels(blob);
      ASSERT_EQ(labels.type(), CV_8UC1);
      ASSERT_EQ(labels.size(), cv::Size(23, 17));
      int mismatches = 0;
      for (int y = 0; y < 17; ++y) {
        for (int x = 0; x < 23; ++x) mismatches += labels.at<uchar>(y, x) != NaiveArgmax(blob, y, x);
      }
      EXPECT_EQ(mismatches, 0) << classes << " classes, coarse " << coarse;
    }
  }
}

TEST(ArgmaxLabels, RefusesWhatIsNotALogitBlob) {
  EXPECT_THROW(ArgmaxLabels(cv::Mat(4, 4, CV_32F, cv::Scalar(0))), Error);  // 2-D
  const int shape[] = {1, 3, 4, 4};
  EXPECT_THROW(ArgmaxLabels(cv::Mat(4, shape, CV_8U, cv::Scalar(0))), Error);  // not float
  const int two_images[] = {2, 3, 4, 4};
  EXPECT_THROW(ArgmaxLabels(cv::Mat(4, two_images, CV_32F, cv::Scalar(0))), Error);
}

TEST(ClassMask, MarksListedClassesOnly) {
  const cv::Mat labels = (cv::Mat_<uchar>(1, 5) << 0, 1, 2, 1, 3);
  const cv::Mat mask = ClassMask(labels, {1, 3});
  const cv::Mat expected = (cv::Mat_<uchar>(1, 5) << 0, 255, 0, 255, 255);
  EXPECT_EQ(cv::countNonZero(mask != expected), 0);
  EXPECT_EQ(cv::countNonZero(ClassMask(labels, {})), 0);
}

TEST(DilateMask, GrowsBySomethingLikeADiscOfTheMargin) {
  cv::Mat dot(41, 41, CV_8UC1, cv::Scalar(0));
  dot.at<uchar>(20, 20) = 255;
  EXPECT_EQ(cv::countNonZero(DilateMask(dot, 0)), 1);
  for (const int margin : {1, 3, 6, 8, 9, 15}) {  // both sides of the switch to the distance transform
    const cv::Mat grown = DilateMask(dot, margin);
    // Along the axes exactly the margin, no further.
    EXPECT_EQ(grown.at<uchar>(20, 20 + margin), 255) << margin;
    EXPECT_EQ(grown.at<uchar>(20 - margin, 20), 255) << margin;
    EXPECT_EQ(grown.at<uchar>(20, 20 + margin + 1), 0) << margin;
    EXPECT_EQ(grown.at<uchar>(20 + margin + 1, 20), 0) << margin;
    // Round, not square: the corner of the bounding square stays out.
    if (margin >= 3) {
      EXPECT_EQ(grown.at<uchar>(20 + margin, 20 + margin), 0) << margin;
    }
    // Area between the inscribed and the bounding square of the disc.
    const double area = cv::countNonZero(grown);
    EXPECT_GT(area, 2.0 * margin * margin) << margin;
    EXPECT_LT(area, (2.0 * margin + 1) * (2.0 * margin + 1)) << margin;
  }
  EXPECT_THROW(DilateMask(dot, -1), Error);
}

TEST(ResultFromLabels, ResizesWithNearestNeighbourAndDilatesOnlyTheDynamicMask) {
  // 2 x 2 network labels onto a 20 x 10 frame: each label becomes a 10 x 5 block.
  const cv::Mat network = (cv::Mat_<uchar>(2, 2) << 0, 1, 2, 0);
  SegmenterOptions options;
  options.dynamic_margin_px = 0;
  SegmentationResult r = ResultFromLabels(network, cv::Size(20, 10), options);
  ASSERT_EQ(r.labels.size(), cv::Size(20, 10));
  EXPECT_EQ(r.labels.at<uchar>(0, 0), 0);
  EXPECT_EQ(r.labels.at<uchar>(4, 19), 1);
  EXPECT_EQ(r.labels.at<uchar>(9, 0), 2);
  EXPECT_EQ(cv::countNonZero(r.dynamic_mask), 50);  // the person block
  EXPECT_EQ(cv::countNonZero(r.movable_mask), 50);  // the chair block
  EXPECT_EQ(r.dynamic_mask.at<uchar>(0, 10), 255);
  EXPECT_EQ(r.dynamic_mask.at<uchar>(0, 9), 0);

  options.dynamic_margin_px = 2;
  r = ResultFromLabels(network, cv::Size(20, 10), options);
  EXPECT_EQ(r.dynamic_mask.at<uchar>(0, 8), 255);  // two pixels left of the person block
  EXPECT_EQ(r.dynamic_mask.at<uchar>(0, 7), 0);
  EXPECT_EQ(r.dynamic_mask.at<uchar>(6, 15), 255);  // two pixels below the block (rows 0-4)
  EXPECT_EQ(r.dynamic_mask.at<uchar>(7, 15), 0);
  EXPECT_EQ(cv::countNonZero(r.movable_mask), 50);   // movable masks are not grown
}

TEST(PropagateResult, GrowsTheDynamicMaskWithTheGap) {
  cv::Mat labels(30, 30, CV_8UC1, cv::Scalar(0));
  labels(cv::Rect(10, 10, 10, 10)).setTo(1);
  SegmenterOptions options;
  options.dynamic_margin_px = 0;
  const SegmentationResult segmented = ResultFromLabels(labels, labels.size(), options);
  const SegmentationResult same = PropagateResult(segmented, 0, 3);
  EXPECT_EQ(cv::countNonZero(same.dynamic_mask), 100);
  const SegmentationResult later = PropagateResult(segmented, 2, 3);  // 6 px more
  EXPECT_EQ(later.propagated_from, 2);
  EXPECT_EQ(later.dynamic_mask.at<uchar>(15, 10 - 6), 255);
  EXPECT_EQ(later.dynamic_mask.at<uchar>(15, 10 - 7), 0);
  EXPECT_EQ(cv::countNonZero(later.labels != segmented.labels), 0);
  EXPECT_EQ(cv::countNonZero(segmented.dynamic_mask), 100);  // the source is untouched
  // Propagated results own their pixels (they go to another thread).
  for (const SegmentationResult* r : {&same, &later}) {
    EXPECT_NE(r->labels.data, segmented.labels.data);
    EXPECT_NE(r->dynamic_mask.data, segmented.dynamic_mask.data);
    EXPECT_NE(r->movable_mask.data, segmented.movable_mask.data);
  }
}

}  // namespace
}  // namespace dlslam::semantic

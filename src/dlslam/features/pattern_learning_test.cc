#include "dlslam/features/pattern_learning.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <tuple>

#include "dlslam/features/test_images.h"
#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

OrientedPatches PatchesOfTexture(int n, unsigned seed) {
  const cv::Mat image = testing::SyntheticTexture(320, 240, seed);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> x(20, 299), y(20, 219);
  std::uniform_real_distribution<float> angle(0.0f, 360.0f);
  OrientedPatches patches;
  for (int i = 0; i < n; ++i) patches.Add(image, x(rng), y(rng), angle(rng));
  return patches;
}

TEST(OrientedPatchesTest, StoresTheDiscAndEvaluatesTests) {
  cv::Mat image(40, 40, CV_8UC1);
  for (int r = 0; r < 40; ++r) {
    for (int c = 0; c < 40; ++c) image.at<uchar>(r, c) = static_cast<uchar>(3 * c + r);
  }
  OrientedPatches patches;
  patches.Add(image, 20, 20, 0.0f);    // unrotated: brighter to the right
  patches.Add(image, 20, 20, 180.0f);  // turned round: brighter to the left
  EXPECT_EQ(patches.size(), 2);
  EXPECT_EQ(patches.PointIndex(kPatternRadius + 1, 0), -1);
  const int i = patches.PointIndex(5, -3);
  ASSERT_GE(i, 0);
  EXPECT_EQ(patches.points()[static_cast<size_t>(i)], cv::Point(5, -3));
  const std::vector<uint64_t> bits = patches.TestBits({-4, 0, 4, 0});  // left < right?
  ASSERT_EQ(bits.size(), 1u);
  EXPECT_EQ(bits[0], 1u);  // true unrotated, false turned round
  EXPECT_THROW(patches.TestBits({16, 0, 0, 0}), Error);
  EXPECT_THROW(patches.Add(image, 10, 20, 0.0f), Error);
}

TEST(LearnPatternTest, PicksValidDecorrelatedLowBiasTests) {
  const OrientedPatches patches = PatchesOfTexture(700, 21);
  PatternLearningOptions options;
  options.candidate_tests = 4000;
  const LearnedPattern learned = LearnPattern(patches, options);
  ASSERT_EQ(learned.tests.size(), static_cast<size_t>(kPatternTests));
  EXPECT_GE(learned.correlation_threshold, options.initial_correlation);
  std::set<std::tuple<int, int, int, int>> unique;
  for (const PatternTest& t : learned.tests) {
    EXPECT_GE(patches.PointIndex(t.x1, t.y1), 0);
    EXPECT_GE(patches.PointIndex(t.x2, t.y2), 0);
    EXPECT_GE(std::max(std::abs(t.x1 - t.x2), std::abs(t.y1 - t.y2)), options.min_separation);
    unique.emplace(t.x1, t.y1, t.x2, t.y2);
  }
  EXPECT_EQ(unique.size(), learned.tests.size());
  const PatternStatistics s = EvaluatePattern(patches, learned.tests);
  EXPECT_LE(s.max_abs_correlation, learned.correlation_threshold + 1e-9);
  const PatternStatistics random = EvaluatePattern(patches, RandomOrbPattern(RandomPatternKind::kUniform, 3));
  EXPECT_LT(s.mean_abs_bias, random.mean_abs_bias);
  EXPECT_LT(s.max_abs_correlation, random.max_abs_correlation);
}

TEST(LearnPatternTest, RejectsTooFewPatchesAndBadOptions) {
  EXPECT_THROW(LearnPattern(PatchesOfTexture(100, 2), {}), Error);
  PatternLearningOptions bad;
  bad.initial_correlation = 0.0;
  EXPECT_THROW(bad.Check(), Error);
  bad = {};
  bad.min_separation = 0;
  EXPECT_THROW(bad.Check(), Error);
  bad = {};
  bad.correlation_step = 2.0;
  EXPECT_THROW(bad.Check(), Error);
}

}  // namespace
}  // namespace dlslam::features

#include "dlslam/features/brief_descriptor.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dlslam/features/matching.h"
#include "dlslam/features/test_images.h"
#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

using Descriptor = std::array<uchar, kDescriptorBytes>;

Descriptor Describe(const SteeredBrief& brief, const cv::Mat& image, cv::Point p, float angle) {
  Descriptor d{};
  brief.Compute(image, p.x, p.y, angle, d.data());
  return d;
}

TEST(SteeredBriefTest, UnrotatedBitsAreThePatternsTests) {
  const cv::Mat image = testing::SyntheticTexture(80, 80, 4);
  const std::span<const PatternTest> pattern = LearnedOrbPattern();
  const SteeredBrief brief(pattern);
  const cv::Point p(40, 37);
  const Descriptor d = Describe(brief, image, p, 0.0f);
  int ones = 0;
  for (int i = 0; i < kPatternTests; ++i) {
    const PatternTest& t = pattern[static_cast<size_t>(i)];
    const bool expected = image.at<uchar>(p.y + t.y1, p.x + t.x1) < image.at<uchar>(p.y + t.y2, p.x + t.x2);
    ASSERT_EQ(((d[static_cast<size_t>(i / 8)] >> (i % 8)) & 1) != 0, expected) << "test " << i;
    ones += expected;
  }
  EXPECT_GT(ones, 40);
  EXPECT_LT(ones, 216);
}

TEST(SteeredBriefTest, RotatedPointsTurnFromXTowardsY) {
  const SteeredBrief brief;
  const PatternTest& t = LearnedOrbPattern()[0];
  EXPECT_EQ(brief.RotatedPoint(0, 0.0f), cv::Point(t.x1, t.y1));
  EXPECT_EQ(brief.RotatedPoint(1, 90.0f), cv::Point(-t.y2, t.x2));
  EXPECT_EQ(brief.RotatedPoint(0, 180.0f), cv::Point(-t.x1, -t.y1));
  const TestRotation r(30.0f);
  EXPECT_EQ(RotateTestPoint(10.0f, 0.0f, r), cv::Point(9, 5));  // (8.66, 5.0)
}

TEST(SteeredBriefTest, SameBitsOnAnImageTurnedByAQuarter) {
  // cv::rotate is exact: pixel (x, y) goes to (rows - 1 - y, x), i.e. the
  // image turns by +90 degrees (x towards y), and so must the tests.
  const cv::Mat image = testing::SyntheticTexture(120, 100, 6);
  cv::Mat turned;
  cv::rotate(image, turned, cv::ROTATE_90_CLOCKWISE);
  const SteeredBrief brief;
  for (const cv::Point& p : {cv::Point(30, 30), cv::Point(60, 50), cv::Point(90, 70)}) {
    const cv::Point q(image.rows - 1 - p.y, p.x);
    for (float angle : {0.0f, 37.0f, 250.0f}) {
      const Descriptor a = Describe(brief, image, p, angle);
      const Descriptor b = Describe(brief, turned, q, std::fmod(angle + 90.0f, 360.0f));
      EXPECT_LE(HammingDistance(a.data(), b.data()), 4) << p << " angle " << angle;
    }
  }
}

TEST(SteeredBriefTest, NearlySameBitsOnAnImageTurnedBy30Degrees) {
  cv::Mat image = testing::SyntheticTexture(200, 200, 8);
  cv::GaussianBlur(image, image, cv::Size(7, 7), 2.0);
  const cv::Point2f centre(99.5f, 99.5f);
  const cv::Mat turn = cv::getRotationMatrix2D(centre, -30.0, 1.0);  // +30 deg in image axes
  cv::Mat turned;
  cv::warpAffine(image, turned, turn, image.size(), cv::INTER_LINEAR);
  const SteeredBrief brief;
  std::vector<int> same_point, other_point;
  for (int y = 70; y <= 130; y += 6) {
    for (int x = 70; x <= 130; x += 6) {
      const cv::Point2d q(turn.at<double>(0, 0) * x + turn.at<double>(0, 1) * y + turn.at<double>(0, 2),
                          turn.at<double>(1, 0) * x + turn.at<double>(1, 1) * y + turn.at<double>(1, 2));
      const Descriptor a = Describe(brief, image, {x, y}, 10.0f);
      const Descriptor b = Describe(brief, turned, {cvRound(q.x), cvRound(q.y)}, 40.0f);
      const Descriptor c = Describe(brief, turned, {cvRound(q.x) + 9, cvRound(q.y) - 7}, 40.0f);
      same_point.push_back(HammingDistance(a.data(), b.data()));
      other_point.push_back(HammingDistance(a.data(), c.data()));
    }
  }
  std::nth_element(same_point.begin(), same_point.begin() + same_point.size() / 2, same_point.end());
  std::nth_element(other_point.begin(), other_point.begin() + other_point.size() / 2, other_point.end());
  EXPECT_LT(same_point[same_point.size() / 2], 40);
  EXPECT_GT(other_point[other_point.size() / 2], 80);
}

TEST(SteeredBriefTest, RejectsBadPatternsAndPatches) {
  std::vector<PatternTest> pattern(LearnedOrbPattern().begin(), LearnedOrbPattern().end());
  pattern[5] = {16, 0, 0, 0};
  EXPECT_THROW(SteeredBrief{pattern}, Error);
  pattern.pop_back();
  EXPECT_THROW(SteeredBrief{pattern}, Error);
  const SteeredBrief brief;
  Descriptor d{};
  const cv::Mat image = testing::SyntheticTexture(64, 64);
  EXPECT_THROW(brief.Compute(image, 14, 30, 0.0f, d.data()), Error);
  EXPECT_THROW(brief.Compute(image, 30, 49, 0.0f, d.data()), Error);
}

TEST(OrbPatternTest, LearnedAndRandomPatternsStayInTheDisc) {
  for (const auto& pattern : {std::vector<PatternTest>(LearnedOrbPattern().begin(), LearnedOrbPattern().end()),
                              RandomOrbPattern(RandomPatternKind::kUniform, 1),
                              RandomOrbPattern(RandomPatternKind::kGaussian, 1)}) {
    ASSERT_EQ(pattern.size(), static_cast<size_t>(kPatternTests));
    for (const PatternTest& t : pattern) {
      EXPECT_LE(t.x1 * t.x1 + t.y1 * t.y1, kPatternRadius * kPatternRadius);
      EXPECT_LE(t.x2 * t.x2 + t.y2 * t.y2, kPatternRadius * kPatternRadius);
      EXPECT_FALSE(t.x1 == t.x2 && t.y1 == t.y2);
    }
  }
  const auto a = RandomOrbPattern(RandomPatternKind::kUniform, 1);
  const auto b = RandomOrbPattern(RandomPatternKind::kUniform, 1);
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), [](const PatternTest& p, const PatternTest& q) {
    return p.x1 == q.x1 && p.y1 == q.y1 && p.x2 == q.x2 && p.y2 == q.y2;
  }));
}

}  // namespace
}  // namespace dlslam::features

#include "dlslam/features/fast_detector.h"

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>
#include <utility>

#include "dlslam/features/test_images.h"
#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

// FAST-9 straight from its definition: 9 contiguous circle pixels all
// brighter than centre + t or all darker than centre - t.
bool IsCornerByDefinition(const cv::Mat& image, int x, int y, int t) {
  static constexpr int kDx[16] = {0, 1, 2, 3, 3, 3, 2, 1, 0, -1, -2, -3, -3, -3, -2, -1};
  static constexpr int kDy[16] = {-3, -3, -2, -1, 0, 1, 2, 3, 3, 3, 2, 1, 0, -1, -2, -3};
  const int centre = image.at<uchar>(y, x);
  for (int sign : {1, -1}) {
    for (int start = 0; start < 16; ++start) {
      bool all = true;
      for (int j = 0; j < 9 && all; ++j) {
        const int k = (start + j) % 16;
        const int v = image.at<uchar>(y + kDy[k], x + kDx[k]);
        all = sign > 0 ? v > centre + t : v < centre - t;
      }
      if (all) return true;
    }
  }
  return false;
}

int ScoreByDefinition(const cv::Mat& image, int x, int y) {
  int score = 0;
  while (score < 255 && IsCornerByDefinition(image, x, y, score + 1)) ++score;
  return score;
}

std::set<std::pair<int, int>> AsSet(const std::vector<cv::Point>& points) {
  std::set<std::pair<int, int>> s;
  for (const cv::Point& p : points) s.emplace(p.x, p.y);
  return s;
}

cv::Mat TestImage() {
  if (auto real = testing::RealFrame("0.000000.jpg")) return *real;
  return testing::SyntheticTexture();
}

TEST(Fast9ScoreTest, MatchesTheDefinitionOnRandomAndTexturedPixels) {
  cv::Mat noise(64, 64, CV_8UC1);
  cv::randu(noise, 0, 256);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(5, 5), 1.5);
  for (const cv::Mat& image : {noise, smooth, testing::SyntheticTexture(64, 64, 3)}) {
    int offsets[16];
    FastCircleOffsets(static_cast<int>(image.step1()), offsets);
    int corners = 0;
    for (int y = 3; y < image.rows - 3; ++y) {
      for (int x = 3; x < image.cols - 3; ++x) {
        const int expected = ScoreByDefinition(image, x, y);
        ASSERT_EQ(Fast9Score(image.ptr<uchar>(y) + x, offsets), expected) << x << "," << y;
        corners += expected >= 7;
      }
    }
    EXPECT_GT(corners, 20);  // the images do exercise corners
  }
}

TEST(Fast9ScoreTest, SaturatedContrast) {
  cv::Mat image(7, 7, CV_8UC1, cv::Scalar(255));
  image.at<uchar>(3, 3) = 0;  // darkest centre, brightest ring: score 254
  int offsets[16];
  FastCircleOffsets(static_cast<int>(image.step1()), offsets);
  EXPECT_EQ(Fast9Score(image.ptr<uchar>(3) + 3, offsets), 254);
  image.setTo(200);
  EXPECT_EQ(Fast9Score(image.ptr<uchar>(3) + 3, offsets), 0);  // flat: no corner
}

TEST(ComputeFastScoresTest, SameCornersAsOpenCvFastWithoutSuppression) {
  const cv::Mat image = TestImage();
  for (int threshold : {7, 20, 40}) {
    std::vector<cv::KeyPoint> reference;
    cv::FAST(image, reference, threshold, false, cv::FastFeatureDetector::TYPE_9_16);
    std::set<std::pair<int, int>> expected;
    for (const cv::KeyPoint& k : reference) {
      expected.emplace(static_cast<int>(k.pt.x), static_cast<int>(k.pt.y));
    }
    cv::Mat scores;
    std::vector<cv::Point> candidates;
    ComputeFastScores(image, cv::Rect(3, 3, image.cols - 6, image.rows - 6), threshold, scores,
                      candidates);
    EXPECT_EQ(AsSet(candidates), expected) << "threshold " << threshold;
    EXPECT_EQ(AsSet(candidates).size(), candidates.size()) << "no corner listed twice";
    EXPECT_GT(candidates.size(), 100u);
    for (const cv::Point& p : candidates) {
      ASSERT_GE(scores.at<uchar>(p), threshold);
    }
  }
}

TEST(ComputeFastScoresTest, NarrowAndOddRegionsAgreeWithTheWholeImage) {
  const cv::Mat image = testing::SyntheticTexture(200, 120, 11);
  cv::Mat whole_scores;
  std::vector<cv::Point> whole;
  const cv::Rect all(3, 3, image.cols - 6, image.rows - 6);
  ComputeFastScores(image, all, 10, whole_scores, whole);
  // Widths below, at and just above one 16-pixel block, and odd offsets.
  for (const cv::Rect& region : {cv::Rect(5, 4, 7, 30), cv::Rect(20, 9, 16, 25),
                                 cv::Rect(41, 17, 17, 40), cv::Rect(60, 3, 37, 50)}) {
    cv::Mat scores;
    std::vector<cv::Point> corners;
    ComputeFastScores(image, region, 10, scores, corners);
    std::vector<cv::Point> expected;
    std::copy_if(whole.begin(), whole.end(), std::back_inserter(expected),
                 [&](const cv::Point& p) { return region.contains(p); });
    EXPECT_EQ(corners, expected) << region;
    EXPECT_EQ(cv::norm(scores(region), whole_scores(region), cv::NORM_INF), 0.0) << region;
  }
}

// Every width from one pixel to past two 32-pixel blocks, so each vector
// path (32 lanes where the CPU has AVX2, 16, one pixel at a time) and each
// overlapping last block meets the one-pixel score.
TEST(ComputeFastScoresTest, EveryWidthScoresEachPixelAsFast9Score) {
  const cv::Mat image = testing::SyntheticTexture(120, 40, 5);
  int offsets[16];
  FastCircleOffsets(static_cast<int>(image.step1()), offsets);
  for (int width = 1; width <= 75; ++width) {
    const cv::Rect region(3 + width % 5, 4, width, 9);
    cv::Mat scores(image.size(), CV_8UC1, cv::Scalar(77));
    std::vector<cv::Point> corners;
    ComputeFastScores(image, region, 12, scores, corners);
    std::vector<cv::Point> expected;
    for (int y = region.y; y < region.br().y; ++y) {
      for (int x = region.x; x < region.br().x; ++x) {
        const int score = Fast9Score(image.ptr<uchar>(y) + x, offsets);
        ASSERT_EQ(scores.at<uchar>(y, x), score >= 12 ? score : 0) << "width " << width << " at " << x << ", " << y;
        if (score >= 12) expected.emplace_back(x, y);
      }
    }
    EXPECT_EQ(corners, expected) << "width " << width;
    EXPECT_EQ(scores.at<uchar>(region.y, region.x - 1), 77) << "pixels outside the region untouched";
    EXPECT_EQ(scores.at<uchar>(region.y, region.br().x), 77);
  }
}

TEST(ComputeFastScoresTest, RejectsRegionsTooCloseToTheEdge) {
  const cv::Mat image = testing::SyntheticTexture(64, 64);
  cv::Mat scores;
  std::vector<cv::Point> corners;
  EXPECT_THROW(ComputeFastScores(image, cv::Rect(2, 3, 10, 10), 10, scores, corners), Error);
  EXPECT_THROW(ComputeFastScores(image, cv::Rect(3, 3, 59, 10), 10, scores, corners), Error);
  EXPECT_THROW(ComputeFastScores(cv::Mat(64, 64, CV_16UC1), cv::Rect(3, 3, 9, 9), 10, scores,
                                 corners),
               Error);
}

TEST(SuppressNonMaximaTest, KeepsStrictLocalMaximaOnly) {
  const cv::Mat image = TestImage();
  const cv::Rect region(4, 4, image.cols - 8, image.rows - 8);
  cv::Mat scores;
  std::vector<cv::Point> candidates;
  ComputeFastScores(image, cv::Rect(3, 3, image.cols - 6, image.rows - 6), 20, scores,
                    candidates);
  std::vector<FastCorner> kept;
  SuppressNonMaxima(scores, candidates, region, 20, kept);
  ASSERT_GT(kept.size(), 50u);
  ASSERT_LT(kept.size(), candidates.size());
  // Reference: every pixel of the region that beats its 8 neighbours.
  std::set<std::pair<int, int>> expected;
  for (int y = region.y; y < region.br().y; ++y) {
    for (int x = region.x; x < region.br().x; ++x) {
      const int s = scores.at<uchar>(y, x);
      bool is_max = s >= 20;
      for (int dy = -1; dy <= 1 && is_max; ++dy) {
        for (int dx = -1; dx <= 1 && is_max; ++dx) {
          if (dx != 0 || dy != 0) is_max = s > scores.at<uchar>(y + dy, x + dx);
        }
      }
      if (is_max) expected.emplace(x, y);
    }
  }
  std::set<std::pair<int, int>> got;
  for (const FastCorner& c : kept) {
    got.emplace(c.x, c.y);
    EXPECT_EQ(c.score, scores.at<uchar>(c.y, c.x));
  }
  EXPECT_EQ(got, expected);
}

TEST(DetectGridFastTest, FallsBackToTheMinimumThresholdInEmptyCells) {
  // Left half: high-contrast texture; right half: the same texture at a
  // contrast too low for the initial threshold but enough for the minimum.
  cv::Mat texture = testing::SyntheticTexture(320, 240, 5);
  cv::Mat image(240, 320, CV_8UC1);
  texture.copyTo(image);
  cv::Mat right = image(cv::Rect(160, 0, 160, 240));
  cv::threshold(right, right, 128, 14, cv::THRESH_BINARY);
  right += 121;  // two grey levels 14 apart: corners at 7, none at 20
  const cv::Rect area(20, 20, 280, 200);
  FastScratch scratch;
  std::vector<FastCorner> with_fallback, without;
  DetectGridFast(image, area, {20, 7, 30}, scratch, with_fallback);
  DetectGridFast(image, area, {20, 20, 30}, scratch, without);
  const auto count_right = [](const std::vector<FastCorner>& corners) {
    return std::count_if(corners.begin(), corners.end(), [](const FastCorner& c) { return c.x >= 165; });
  };
  EXPECT_EQ(count_right(without), 0);
  EXPECT_GT(count_right(with_fallback), 20);
  for (const FastCorner& c : with_fallback) {
    ASSERT_TRUE(area.contains(cv::Point(c.x, c.y)));
    ASSERT_GE(c.score, c.x >= 165 ? 7 : 20) << c.x << "," << c.y;
  }
}

TEST(DetectGridFastTest, ListsEachPixelOnceWhateverTheCellSize) {
  // Low-contrast right half: many cells fall back, next to cells that did not.
  cv::Mat image = TestImage().clone();
  cv::Mat right = image(cv::Rect(image.cols / 2, 0, image.cols / 2, image.rows));
  right.convertTo(right, CV_8U, 0.2, 100);
  FastScratch scratch;
  for (int cell : {8, 13, 30, 31, 47}) {
    for (const cv::Rect& area : {cv::Rect(19, 19, image.cols - 38, image.rows - 38),
                                 cv::Rect(23, 21, 101, 77)}) {
      std::vector<FastCorner> corners;
      DetectGridFast(image, area, {20, 7, cell}, scratch, corners);
      std::set<std::pair<int, int>> unique;
      for (const FastCorner& c : corners) unique.emplace(c.x, c.y);
      EXPECT_EQ(unique.size(), corners.size()) << "cell " << cell << " area " << area;
      EXPECT_GT(corners.size(), 10u);
    }
  }
}

// Skipping cells (those wholly inside an exclusion mask) changes nothing for
// the others: the same corners, scores and order as the full search with the
// skipped cells' corners dropped, fallback cells included.
TEST(DetectGridFastTest, SkippedCellsLeaveTheOthersExactlyAsTheyWere) {
  cv::Mat image = TestImage().clone();
  cv::Mat right = image(cv::Rect(image.cols / 2, 0, image.cols / 2, image.rows));
  right.convertTo(right, CV_8U, 0.2, 100);  // cells that fall back
  cv::RNG rng(7);
  FastScratch scratch;
  for (int cell : {13, 30, 47}) {
    const cv::Rect area(19, 19, image.cols - 38, image.rows - 38);
    const FastGrid grid(area, cell);
    std::vector<FastCorner> all;
    DetectGridFast(image, area, {20, 7, cell}, scratch, all);
    for (double share : {0.1, 0.5, 0.9}) {
      std::vector<bool> skip(static_cast<size_t>(grid.size()));
      for (size_t k = 0; k < skip.size(); ++k) skip[k] = rng.uniform(0.0, 1.0) < share;
      std::vector<FastCorner> expected;
      for (const FastCorner& c : all) {
        if (!skip[static_cast<size_t>(grid.Index(grid.RowOf(c.y), grid.ColOf(c.x)))]) expected.push_back(c);
      }
      std::vector<FastCorner> got;
      DetectGridFast(image, area, {20, 7, cell}, scratch, got, skip);
      ASSERT_EQ(got.size(), expected.size()) << "cell " << cell << " share " << share;
      for (size_t k = 0; k < got.size(); ++k) {
        ASSERT_EQ(std::tie(got[k].x, got[k].y, got[k].score), std::tie(expected[k].x, expected[k].y, expected[k].score))
            << "corner " << k << " cell " << cell << " share " << share;
      }
      EXPECT_LT(got.size(), all.size());
    }
  }
  std::vector<FastCorner> corners;
  EXPECT_THROW(DetectGridFast(image, cv::Rect(19, 19, 100, 100), {20, 7, 30}, scratch, corners, std::vector<bool>(3)),
               Error);
}

TEST(FastGridTest, CellsTileTheAreaAndEachPixelFindsItsCell) {
  for (const cv::Rect& area : {cv::Rect(19, 19, 602, 442), cv::Rect(3, 5, 29, 7), cv::Rect(0, 0, 31, 90)}) {
    for (int size : {1, 7, 30, 100}) {
      const FastGrid grid(area, size);
      int covered = 0;
      for (int row = 0; row < grid.rows; ++row) {
        for (int col = 0; col < grid.cols; ++col) {
          const cv::Rect cell = grid.Cell(row, col);
          covered += cell.area();
          for (int y = cell.y; y < cell.y + cell.height; ++y) {
            for (int x = cell.x; x < cell.x + cell.width; ++x) {
              ASSERT_EQ(grid.RowOf(y), row);
              ASSERT_EQ(grid.ColOf(x), col);
            }
          }
        }
      }
      EXPECT_EQ(covered, area.area()) << area << " cell " << size;
    }
  }
}

}  // namespace
}  // namespace dlslam::features

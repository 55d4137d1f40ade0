#include "dlslam/features/orb_extractor.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "dlslam/features/test_images.h"
#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

std::vector<std::pair<std::string, cv::Mat>> Images() {
  std::vector<std::pair<std::string, cv::Mat>> images = {{"synthetic", testing::SyntheticTexture()}};
  if (auto real = testing::RealFrame("0.000000.jpg")) images.emplace_back("7scenes 0", *real);
  if (auto real = testing::RealFrame("10.000000.jpg")) images.emplace_back("7scenes 10", *real);
  return images;
}

TEST(OrbExtractorTest, CountNearTheTargetAndSpreadOverTheImage) {
  OrbExtractor orb;
  for (const auto& [name, image] : Images()) {
    const OrbFeatures f = orb.Extract(image);
    const int n = static_cast<int>(f.keypoints.size());
    EXPECT_GE(n, 900) << name;
    EXPECT_LE(n, 1000) << name;
    ASSERT_EQ(f.descriptors.rows, n);
    EXPECT_EQ(f.descriptors.cols, kDescriptorBytes);
    EXPECT_EQ(f.descriptors.type(), CV_8UC1);
    int quadrant[4] = {};
    std::vector<int> per_level(8, 0);
    for (const cv::KeyPoint& k : f.keypoints) {
      ++quadrant[(k.pt.x >= image.cols / 2 ? 1 : 0) + (k.pt.y >= image.rows / 2 ? 2 : 0)];
      ASSERT_GE(k.octave, 0);
      ASSERT_LT(k.octave, 8);
      ++per_level[static_cast<size_t>(k.octave)];
      const double scale = std::pow(1.2, k.octave);
      EXPECT_NEAR(k.size, 31 * scale, 1e-3);
      // Whole patch inside the level image (19 px edge border at the level).
      EXPECT_GE(k.pt.x / scale, 18.999) << name;
      EXPECT_GE(k.pt.y / scale, 18.999) << name;
      EXPECT_LT(k.pt.x / scale, image.cols / scale - 18.0) << name;
      EXPECT_LT(k.pt.y / scale, image.rows / scale - 18.0) << name;
      EXPECT_GE(k.angle, 0.0f);
      EXPECT_LT(k.angle, 360.0f);
      EXPECT_GT(k.response, 0.0f);
    }
    for (int q = 0; q < 4; ++q) EXPECT_GT(quadrant[q], n / 10) << name << " quadrant " << q;
    // The finest level gets the most, as the per-level targets say.
    EXPECT_GT(per_level[0], per_level[7]) << name;
    EXPECT_GT(per_level[7], 0) << name;
  }
}

TEST(OrbExtractorTest, DeterministicAndColourIsConvertedToGrey) {
  const cv::Mat grey = testing::SyntheticTexture();
  cv::Mat bgr, bgra;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(grey, bgra, cv::COLOR_GRAY2BGRA);
  OrbExtractor orb;
  const OrbFeatures a = orb.Extract(grey);
  for (const cv::Mat& input : {grey, bgr, bgra}) {
    const OrbFeatures b = orb.Extract(input);
    ASSERT_EQ(a.keypoints.size(), b.keypoints.size());
    for (size_t i = 0; i < a.keypoints.size(); ++i) {
      ASSERT_EQ(a.keypoints[i].pt, b.keypoints[i].pt);
      ASSERT_EQ(a.keypoints[i].angle, b.keypoints[i].angle);
    }
    EXPECT_EQ(cv::norm(a.descriptors, b.descriptors, cv::NORM_HAMMING), 0.0);
  }
}

TEST(OrbExtractorTest, ExclusionMaskDropsKeypointsAndMovesTheBudget) {
  const cv::Mat image = testing::SyntheticTexture();
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(0, 0, 320, 480)).setTo(255);       // left half excluded
  mask(cv::Rect(400, 100, 100, 100)).setTo(1);     // any non-zero value excludes
  OrbExtractor orb;
  const OrbFeatures f = orb.Extract(image, mask);
  EXPECT_GE(f.keypoints.size(), 800u);
  EXPECT_EQ(f.descriptors.rows, static_cast<int>(f.keypoints.size()));
  for (const cv::KeyPoint& k : f.keypoints) {
    ASSERT_EQ(mask.at<uchar>(cvRound(k.pt.y), cvRound(k.pt.x)), 0) << k.pt;
  }
}

// The distance [px, level 0] from `k` to the nearest non-zero pixel of
// `mask` (Chebyshev), capped at `cap`.
int DistanceToMask(const cv::Mat& mask, const cv::KeyPoint& k, int cap) {
  const int x = cvRound(k.pt.x), y = cvRound(k.pt.y);
  for (int d = 0; d <= cap; ++d) {
    for (int yy = std::max(y - d, 0); yy <= std::min(y + d, mask.rows - 1); ++yy) {
      for (int xx = std::max(x - d, 0); xx <= std::min(x + d, mask.cols - 1); ++xx) {
        if (mask.at<uchar>(yy, xx) != 0) return d;
      }
    }
  }
  return cap + 1;
}

TEST(OrbExtractorTest, NoKeypointSeesAnExcludedPixelWithFast) {
  // Keypoints next to a person's outline may be corners of the outline: the
  // pixels FAST compared (radius exclusion_radius at the keypoint's level)
  // must all lie outside the mask.
  for (const auto& [name, image] : Images()) {
    cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
    cv::ellipse(mask, {250, 260}, {90, 200}, 0, 0, 360, cv::Scalar(255), cv::FILLED);  // a person
    mask(cv::Rect(450, 100, 60, 300)).setTo(255);                                        // another
    OrbOptions options;
    options.exclusion_radius = 3;
    OrbExtractor orb(options);
    const OrbFeatures f = orb.Extract(image, mask);
    ASSERT_GE(f.keypoints.size(), 700u) << name;
    int closest_margin = 1000;  // the smallest distance left over the reach, in px
    for (const cv::KeyPoint& k : f.keypoints) {
      // The level's +-3 px box reaches ceil(3 * scale) px at level 0.
      const int reach = static_cast<int>(std::ceil(options.exclusion_radius * std::pow(1.2, k.octave)));
      const int d = DistanceToMask(mask, k, reach + 2);
      ASSERT_GT(d, reach) << name << " keypoint " << k.pt << " level " << k.octave;
      closest_margin = std::min(closest_margin, d - reach);
    }
    EXPECT_LE(closest_margin, 2) << name << ": the mask's outline has keypoints right outside the reach";
    // Radius 0: only the keypoint's own pixel counts, some sit right at the outline.
    options.exclusion_radius = 0;
    OrbExtractor centre_only(options);
    const OrbFeatures g = centre_only.Extract(image, mask);
    int at_outline = 0;
    for (const cv::KeyPoint& k : g.keypoints) {
      const int d = DistanceToMask(mask, k, 3);
      ASSERT_GT(d, 0) << name;
      at_outline += d <= 3;
    }
    EXPECT_GT(at_outline, 0) << name;
  }
}

void ExpectSameFeatures(const OrbFeatures& a, const OrbFeatures& b) {
  ASSERT_EQ(a.keypoints.size(), b.keypoints.size());
  for (std::size_t i = 0; i < a.keypoints.size(); ++i) {
    ASSERT_EQ(a.keypoints[i].pt, b.keypoints[i].pt) << i;
    ASSERT_EQ(a.keypoints[i].octave, b.keypoints[i].octave) << i;
    ASSERT_EQ(a.keypoints[i].angle, b.keypoints[i].angle) << i;
  }
  EXPECT_EQ(cv::norm(a.descriptors, b.descriptors, cv::NORM_HAMMING), 0.0);
}

TEST(OrbExtractorTest, ReextractGivesWhatAFreshExtractionOutsideTheGrownMaskGives) {
  const cv::Mat image = testing::SyntheticTexture();
  cv::Mat first(image.size(), CV_8UC1, cv::Scalar(0));
  first(cv::Rect(100, 50, 200, 300)).setTo(255);
  cv::Mat grown = first.clone();  // covers the first: its corners are filtered again
  grown(cv::Rect(350, 200, 150, 200)).setTo(7);
  cv::Mat other(image.size(), CV_8UC1, cv::Scalar(0));  // does not: FAST runs again
  other(cv::Rect(0, 300, 640, 100)).setTo(255);
  for (const cv::Mat& second : {grown, other, cv::Mat()}) {
    OrbExtractor orb;
    const OrbFeatures a = orb.Extract(image, first);
    const OrbFeatures again = orb.Reextract(second);
    OrbExtractor fresh;
    ExpectSameFeatures(again, fresh.Extract(image, second));
    if (!second.empty()) {  // the keypoints did move (to where the first mask allowed none or fewer)
      EXPECT_TRUE(again.descriptors.rows != a.descriptors.rows ||
                  cv::norm(again.descriptors, a.descriptors, cv::NORM_HAMMING) != 0.0);
    }
  }
  // From a whole-image extraction too, and twice in a row.
  OrbExtractor orb;
  orb.Extract(image);
  OrbExtractor fresh;
  ExpectSameFeatures(orb.Reextract(first), fresh.Extract(image, first));
  ExpectSameFeatures(orb.Reextract(grown), fresh.Extract(image, grown));
}

TEST(OrbExtractorTest, ExtractOnAnotherExtractorsPyramidGivesWhatItsOwnExtractionGives) {
  const cv::Mat image = testing::SyntheticTexture();
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(100, 50, 200, 300)).setTo(255);
  OrbOptions low;  // other FAST thresholds, the same pyramid
  low.fast_threshold_initial = 8;
  low.fast_threshold_min = 4;
  OrbExtractor source, second(low), fresh(low);
  ASSERT_TRUE(second.CanExtractOn(source));
  EXPECT_THROW(second.ExtractOn(source, mask), Error);  // the source has not extracted yet
  cv::Mat colour;
  cv::cvtColor(image, colour, cv::COLOR_GRAY2BGR);
  source.Extract(colour);
  const OrbFeatures on = second.ExtractOn(source, mask);
  ExpectSameFeatures(on, fresh.Extract(image, mask));
  cv::Mat grown = mask.clone();
  grown(cv::Rect(400, 100, 100, 100)).setTo(255);
  ExpectSameFeatures(second.Reextract(grown), fresh.Extract(image, grown));
  // Its own next extraction does not write into the source's levels.
  const cv::Mat source_level1 = source.pyramid()[1].clone();
  second.Extract(testing::SyntheticTexture(640, 480, 9));
  EXPECT_EQ(cv::norm(source.pyramid()[1], source_level1, cv::NORM_INF), 0.0);
  OrbOptions other_levels;
  other_levels.n_levels = 6;
  OrbExtractor different(other_levels);
  EXPECT_FALSE(different.CanExtractOn(source));
  EXPECT_THROW(different.ExtractOn(source, mask), Error);
}

TEST(OrbExtractorTest, ExtractOnWithOtherTestsDescribesItsOwnWay) {
  // Descriptors of the source's corners are reused only with the same tests.
  const cv::Mat image = testing::SyntheticTexture();
  std::vector<PatternTest> reversed(LearnedOrbPattern().begin(), LearnedOrbPattern().end());
  std::reverse(reversed.begin(), reversed.end());
  OrbExtractor source, second({}, reversed), fresh({}, reversed);
  source.Extract(image);
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(100, 50, 200, 300)).setTo(255);
  const OrbFeatures on = second.ExtractOn(source, mask);
  const OrbFeatures own = fresh.Extract(image, mask);
  ExpectSameFeatures(on, own);
  ASSERT_GT(on.keypoints.size(), 100u);
  const OrbFeatures source_features = source.Reextract(mask);  // the source's tests, the same corners
  ASSERT_EQ(source_features.keypoints.size(), on.keypoints.size());
  EXPECT_GT(cv::norm(source_features.descriptors, on.descriptors, cv::NORM_HAMMING), 0.0);
}

TEST(OrbExtractorTest, ReextractNeedsAnExtractionOfTheSameSize) {
  OrbExtractor orb;
  const cv::Mat image = testing::SyntheticTexture();
  EXPECT_THROW(orb.Reextract(cv::Mat()), Error);
  orb.Extract(image);
  EXPECT_THROW(orb.Reextract(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0))), Error);
  EXPECT_THROW(orb.Reextract(cv::Mat(image.size(), CV_16UC1, cv::Scalar(0))), Error);
  orb.Describe(image, {});
  EXPECT_THROW(orb.Reextract(cv::Mat()), Error);  // Describe rebuilt the pyramid without corners
}

TEST(OrbExtractorTest, DescribeReproducesTheDescriptorsOfGivenKeypoints) {
  const cv::Mat image = testing::SyntheticTexture();
  OrbExtractor orb;
  const OrbFeatures f = orb.Extract(image);
  std::vector<cv::KeyPoint> keypoints = f.keypoints;
  keypoints.emplace_back(5.0f, 5.0f, 31.0f, 0.0f, 1.0f, 0);     // patch leaves the image
  keypoints.emplace_back(300.0f, 200.0f, 31.0f, 0.0f, 1.0f, 9);  // no such level
  const OrbFeatures d = orb.Describe(image, keypoints);
  ASSERT_EQ(d.keypoints.size(), f.keypoints.size());
  EXPECT_EQ(cv::norm(d.descriptors, f.descriptors, cv::NORM_HAMMING), 0.0);
}

TEST(OrbExtractorTest, RejectsBadInput) {
  OrbExtractor orb;
  const cv::Mat image = testing::SyntheticTexture();
  EXPECT_THROW(orb.Extract(cv::Mat()), Error);
  EXPECT_THROW(orb.Extract(cv::Mat(480, 640, CV_16UC1, cv::Scalar(1000))), Error);
  EXPECT_THROW(orb.Extract(cv::Mat(480, 640, CV_32FC1, cv::Scalar(0.5))), Error);
  EXPECT_THROW(orb.Extract(cv::Mat(480, 640, CV_8UC2, cv::Scalar(1))), Error);
  EXPECT_THROW(orb.Extract(image(cv::Rect(0, 0, 38, 300))), Error);  // needs 2 * 19 + 1
  EXPECT_NO_THROW(orb.Extract(image(cv::Rect(0, 0, 39, 39))));
  EXPECT_THROW(orb.Extract(image, cv::Mat(100, 100, CV_8UC1, cv::Scalar(0))), Error);
  EXPECT_THROW(orb.Extract(image, cv::Mat(image.size(), CV_16UC1, cv::Scalar(0))), Error);
  try {
    orb.Extract(cv::Mat(480, 640, CV_16UC1));
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("16U"), std::string::npos) << e.what();
  }
}

TEST(OrbExtractorTest, SmallImagesGetKeypointsOnTheLevelsThatFit) {
  OrbExtractor orb;
  const OrbFeatures f = orb.Extract(testing::SyntheticTexture(120, 90, 2));
  EXPECT_GT(f.keypoints.size(), 20u);
  // round(90 / 1.2^4) = 43 still leaves an area inside the 19 px borders; 36 does not.
  for (const cv::KeyPoint& k : f.keypoints) EXPECT_LE(k.octave, 4);
}

TEST(OrbOptionsTest, CheckNamesTheBadField) {
  EXPECT_NO_THROW(OrbOptions{}.Check());
  const auto expect_bad = [](auto change, const std::string& field) {
    OrbOptions o;
    change(o);
    try {
      o.Check();
      ADD_FAILURE() << field << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  expect_bad([](OrbOptions& o) { o.n_features = 0; }, "n_features");
  expect_bad([](OrbOptions& o) { o.n_levels = 0; }, "n_levels");
  expect_bad([](OrbOptions& o) { o.scale_factor = 1.0; }, "scale_factor");
  expect_bad([](OrbOptions& o) { o.fast_threshold_initial = 0; }, "fast_threshold_initial");
  expect_bad([](OrbOptions& o) { o.fast_threshold_min = 21; }, "fast_threshold_min");
  expect_bad([](OrbOptions& o) { o.cell_size = 4; }, "cell_size");
  expect_bad([](OrbOptions& o) { o.edge_border = 15; }, "edge_border");
  expect_bad([](OrbOptions& o) { o.exclusion_radius = -1; }, "exclusion_radius");
  expect_bad([](OrbOptions& o) { o.exclusion_radius = 16; }, "exclusion_radius");
  OrbOptions bad;
  bad.n_levels = -1;
  EXPECT_THROW(OrbExtractor{bad}, Error);
}

TEST(OrbOptionsTest, LevelTargetsFormAGeometricSeriesSummingToTheTotal) {
  for (int n : {1000, 1500, 7}) {
    OrbOptions o;
    o.n_features = n;
    const std::vector<int> targets = LevelFeatureTargets(o);
    ASSERT_EQ(targets.size(), 8u);
    int sum = 0;
    for (int t : targets) {
      EXPECT_GE(t, 0);
      sum += t;
    }
    EXPECT_EQ(sum, n);
  }
  const std::vector<int> t = LevelFeatureTargets(OrbOptions{});
  // First term N (1 - r) / (1 - r^8) with r = 1 / 1.2: 217.
  EXPECT_EQ(t[0], 217);
  for (size_t l = 1; l + 1 < t.size(); ++l) EXPECT_NEAR(t[l], t[l - 1] / 1.2, 1.0);
  const std::vector<double> scales = LevelScales(OrbOptions{});
  EXPECT_NEAR(scales[7], std::pow(1.2, 7), 1e-12);
}

}  // namespace
}  // namespace dlslam::features

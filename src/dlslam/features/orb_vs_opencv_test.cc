// Our extractor against cv::ORB (same n_features / levels / scale, its
// default HARRIS_SCORE) on real frames turned and scaled by known transforms:
// repeatability and matching precision / recall must be within a small
// margin of OpenCV's. Full numbers: tools/orb_eval and docs/features.md.

#include <gtest/gtest.h>
#include <fmt/format.h>
#include <opencv2/features2d.hpp>

#include <iostream>
#include <string>

#include "dlslam/features/evaluation.h"
#include "dlslam/features/orb_extractor.h"
#include "dlslam/features/test_images.h"
#include "tests/support/test_data.h"

namespace dlslam::features {
namespace {

struct Case {
  double angle_deg, scale;
};

TransformScores& operator+=(TransformScores& a, const TransformScores& b) {
  a.keypoints_a += b.keypoints_a;
  a.keypoints_b += b.keypoints_b;
  a.repeated += b.repeated;
  a.repeated_by_chance += b.repeated_by_chance;
  a.matches += b.matches;
  a.correct_matches += b.correct_matches;
  return a;
}

std::string Describe(const TransformScores& s) {
  return fmt::format("repeatability {:.3f} (by chance {:.3f}) precision {:.3f} recall {:.3f}",
                     s.repeatability(), s.chance_repeatability(), s.precision(), s.recall());
}

// Margins below cv::ORB. The descriptor alone (ours on cv::ORB's keypoints
// and angles) is held close. The detector, as ORB-SLAM designs it, spreads
// keypoints evenly and takes weak corners (FAST threshold 7) in cells
// without strong ones, about a third of them; cv::ORB keeps the strongest
// corners wherever they cluster, which also raises its repeatability by
// chance (see chance_repeatability). On these frames ours is measured up to
// 0.185 below in repeatability, 0.047 in precision and 0.113 in recall
// (repeatability 0.072 below without the fallback); the descriptor alone
// 0.008 in precision and 0.016 in recall. Full numbers: docs/features.md.
constexpr double kOursRepeatability = 0.22, kOursPrecision = 0.07, kOursRecall = 0.14;
constexpr double kNoFallbackRepeatability = 0.12;
constexpr double kDescriptorPrecision = 0.015, kDescriptorRecall = 0.03;

class OrbVsOpenCvTest : public ::testing::TestWithParam<Case> {};

TEST_P(OrbVsOpenCvTest, WithinAMarginOfOpenCvUnderAKnownTransform) {
  DLSLAM_REQUIRE_SHARED_DATA(rgb, "7scenes-redkitchen-500/rgb");
  const Case c = GetParam();
  OrbExtractor ours;
  OrbOptions no_fallback_options;
  no_fallback_options.fast_threshold_min = no_fallback_options.fast_threshold_initial;
  OrbExtractor ours_no_fallback(no_fallback_options);
  const auto theirs = cv::ORB::create(1000, 1.2f, 8);  // HARRIS_SCORE, as by default
  TransformScores ours_total, theirs_total, descriptor_total, no_fallback_total;
  for (const char* name : {"0.000000.jpg", "5.000000.jpg", "10.000000.jpg"}) {
    const cv::Mat image = *testing::RealFrame(name);
    const WarpedImage warped = WarpImage(image, c.angle_deg, c.scale);
    const auto extract_ours = [](OrbExtractor& extractor, const cv::Mat& m) {
      OrbFeatures f = extractor.Extract(m);
      return Features{std::move(f.keypoints), f.descriptors};
    };
    const auto extract_theirs = [&](const cv::Mat& m) {
      Features f;
      theirs->detectAndCompute(m, cv::noArray(), f.keypoints, f.descriptors);
      return f;
    };
    const auto describe_theirs = [&](const cv::Mat& m) {
      OrbFeatures f = ours.Describe(m, extract_theirs(m).keypoints);
      return Features{std::move(f.keypoints), f.descriptors};
    };
    ours_total += ScoreUnderTransform(extract_ours(ours, image), extract_ours(ours, warped.image), warped);
    no_fallback_total += ScoreUnderTransform(extract_ours(ours_no_fallback, image),
                                             extract_ours(ours_no_fallback, warped.image), warped);
    theirs_total += ScoreUnderTransform(extract_theirs(image), extract_theirs(warped.image), warped);
    descriptor_total += ScoreUnderTransform(describe_theirs(image), describe_theirs(warped.image), warped);
  }
  std::cout << "ours:              " << Describe(ours_total) << "\n"
            << "ours, no fallback: " << Describe(no_fallback_total) << "\n"
            << "cv::ORB:           " << Describe(theirs_total) << "\n"
            << "cv kp + our desc:  " << Describe(descriptor_total) << "\n";
  EXPECT_GT(ours_total.matches, 300);
  EXPECT_GE(ours_total.repeatability(), theirs_total.repeatability() - kOursRepeatability);
  EXPECT_GE(ours_total.precision(), theirs_total.precision() - kOursPrecision);
  EXPECT_GE(ours_total.recall(), theirs_total.recall() - kOursRecall);
  EXPECT_GE(descriptor_total.precision(), theirs_total.precision() - kDescriptorPrecision);
  EXPECT_GE(descriptor_total.recall(), theirs_total.recall() - kDescriptorRecall);
  EXPECT_GE(no_fallback_total.repeatability(), theirs_total.repeatability() - kNoFallbackRepeatability);
}

INSTANTIATE_TEST_SUITE_P(RotationsAndScales, OrbVsOpenCvTest,
                         ::testing::Values(Case{30, 1.0}, Case{60, 1.0}, Case{90, 1.0},
                                           Case{0, 0.8}, Case{0, 1.25}));

}  // namespace
}  // namespace dlslam::features

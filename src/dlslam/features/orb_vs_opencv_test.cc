// Our extractor against cv::ORB (same n_features / levels / scale, its
// default HARRIS_SCORE) on real frames turned and scaled by known transforms:
// repeatability and matching precision / recall must be within a small
// margin of OpenCV's. Full numbers: tools/orb_eval and docs/features.md.

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>

#include <fmt/format.h>

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
  a.matches += b.matches;
  a.correct_matches += b.correct_matches;
  return a;
}

class OrbVsOpenCvTest : public ::testing::TestWithParam<Case> {};

TEST_P(OrbVsOpenCvTest, WithinAMarginOfOpenCvUnderAKnownTransform) {
  DLSLAM_REQUIRE_SHARED_DATA(rgb, "7scenes-redkitchen-500/rgb");
  const Case c = GetParam();
  OrbExtractor ours;
  const auto theirs = cv::ORB::create(1000, 1.2f, 8);
  TransformScores ours_total, theirs_total;
  for (const char* name : {"0.000000.jpg", "5.000000.jpg", "10.000000.jpg"}) {
    const cv::Mat image = *testing::RealFrame(name);
    const WarpedImage warped = WarpImage(image, c.angle_deg, c.scale);
    const auto extract_ours = [&](const cv::Mat& m) {
      OrbFeatures f = ours.Extract(m);
      return Features{std::move(f.keypoints), f.descriptors};
    };
    const auto extract_theirs = [&](const cv::Mat& m) {
      Features f;
      theirs->detectAndCompute(m, cv::noArray(), f.keypoints, f.descriptors);
      return f;
    };
    ours_total += ScoreUnderTransform(extract_ours(image), extract_ours(warped.image), warped);
    theirs_total += ScoreUnderTransform(extract_theirs(image), extract_theirs(warped.image), warped);
  }
  RecordProperty("ours", fmt::format("rep {:.3f} prec {:.3f} rec {:.3f}", ours_total.repeatability(),
                                     ours_total.precision(), ours_total.recall()));
  RecordProperty("opencv", fmt::format("rep {:.3f} prec {:.3f} rec {:.3f}", theirs_total.repeatability(),
                                       theirs_total.precision(), theirs_total.recall()));
  EXPECT_GT(ours_total.matches, 300);
  EXPECT_GE(ours_total.repeatability(), theirs_total.repeatability() - kRepeatabilityMargin);
  EXPECT_GE(ours_total.precision(), theirs_total.precision() - kPrecisionMargin);
  EXPECT_GE(ours_total.recall(), theirs_total.recall() - kRecallMargin);
}

INSTANTIATE_TEST_SUITE_P(RotationsAndScales, OrbVsOpenCvTest,
                         ::testing::Values(Case{30, 1.0}, Case{60, 1.0}, Case{90, 1.0},
                                           Case{0, 0.8}, Case{0, 1.25}));

}  // namespace
}  // namespace dlslam::features

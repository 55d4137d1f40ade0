#include "dlslam/tracking/relocalizer.h"

#include <gtest/gtest.h>

#include <memory>

#include "dlslam/place/vocabulary_file.h"
#include "dlslam/util/check.h"

namespace dlslam {
namespace {

TEST(RelocalizerOptions, CheckNamesBadValues) {
  EXPECT_NO_THROW(RelocalizerOptions().Check());
  RelocalizerOptions o;
  o.min_bow_matches = 3;  // PnP needs 4
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.min_inliers = 5;  // below min_first_inliers
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.ransac_reprojection_px = 0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.bow_match.ratio = 1.5;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.max_candidates = 0;
  EXPECT_THROW(o.Check(), Error);
}

TEST(Relocalizer, NothingToFindInAnEmptyMap) {
  const auto vocabulary = std::make_shared<const place::Vocabulary>(place::LoadVocabulary(place::FindVocabulary()));
  const place::KeyFrameIndex index(vocabulary);
  const Map map;
  const Relocalizer relocalizer({}, &map, &index);
  cv::Mat descriptors(20, 32, CV_8UC1);
  cv::randu(descriptors, 0, 256);
  std::vector<cv::KeyPoint> keypoints;
  for (int i = 0; i < 20; ++i) keypoints.emplace_back(20.f * static_cast<float>(i) + 10.f, 100.f, 31.f);
  const Frame frame =
      Frame::Create(0.0, keypoints, descriptors, cv::Mat(), CameraPreset("freiburg3"), ScalePyramid{});
  const RelocalizationAttempt attempt = relocalizer.Relocalize(frame);
  EXPECT_FALSE(attempt.result.has_value());
  EXPECT_EQ(attempt.candidates, 0);
  EXPECT_THROW(Relocalizer({}, &map, nullptr), Error);
}

}  // namespace
}  // namespace dlslam

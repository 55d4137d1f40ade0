#pragma once
// Learning the 256 ORB tests from data (Rublee et al. 2011, section 4.3):
// sample oriented patches around keypoints of real images, enumerate
// candidate point-pair tests inside the patch, and greedily pick tests whose
// mean is near 0.5 and whose correlation with the tests already picked is
// low, raising the correlation threshold until 256 are found.

#include <opencv2/core.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "dlslam/features/orb_pattern.h"

namespace dlslam::features {

// Smoothed intensities at every integer point of the disc of radius
// kPatternRadius, for many keypoints, each patch rotated to its keypoint's
// orientation exactly as SteeredBrief reads it. Stored point by point.
class OrientedPatches {
 public:
  OrientedPatches();

  // Samples the patch around pixel (x, y) of `smoothed` (8-bit grey, 15 px
  // or more from the edges) rotated by `angle_deg`.
  void Add(const cv::Mat& smoothed, int x, int y, float angle_deg);

  int size() const { return n_patches_; }
  const std::vector<cv::Point>& points() const { return points_; }
  // Index of disc point (x, y) in points(), -1 outside the disc.
  int PointIndex(int x, int y) const;
  // The test's outcome I(p1) < I(p2) on every patch, packed 64 per word.
  std::vector<uint64_t> TestBits(const PatternTest& test) const;

 private:
  std::vector<cv::Point> points_;
  std::vector<std::vector<uchar>> values_;  // [point][patch]
  int n_patches_ = 0;
};

struct PatternLearningOptions {
  // Candidate tests drawn at random from all allowed point pairs of the
  // disc (about 130 000); 0 = all of them.
  int candidate_tests = 40000;
  // The two points of a test differ by at least this much in x or y [px]:
  // the paper's 5 x 5 sub-windows that must not overlap.
  int min_separation = 5;
  // Largest |correlation| with the tests already picked, in (0, 1]; raised
  // by correlation_step until kPatternTests tests are picked.
  double initial_correlation = 0.2;
  double correlation_step = 0.05;  // in (0, 1]
  uint32_t seed = 1;               // for drawing the candidates

  void Check() const;  // throws dlslam::Error
};

struct LearnedPattern {
  std::vector<PatternTest> tests;  // kPatternTests, in the order picked
  double correlation_threshold = 0.0;  // the threshold that yielded them
  int candidates = 0;                  // candidate tests considered
};

// Throws dlslam::Error when the patches cannot yield kPatternTests tests
// (e.g. too few patches).
LearnedPattern LearnPattern(const OrientedPatches& patches, const PatternLearningOptions& options);

struct PatternStatistics {
  double mean_bit = 0.0;              // mean over tests of the fraction of 1s
  double mean_abs_bias = 0.0;         // mean over tests of |fraction of 1s - 0.5|
  double mean_abs_correlation = 0.0;  // mean |Pearson correlation| over pairs of tests
  double max_abs_correlation = 0.0;
};
// Statistics of a pattern's bits over the patches (tests inside the disc).
PatternStatistics EvaluatePattern(const OrientedPatches& patches,
                                  std::span<const PatternTest> pattern);

}  // namespace dlslam::features

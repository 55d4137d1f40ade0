#include "dlslam/features/pattern_learning.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <random>

#include "dlslam/features/brief_descriptor.h"
#include "dlslam/features/orb_options.h"
#include "dlslam/util/check.h"
#include "dlslam/util/cpu_dispatch.h"

namespace dlslam::features {
namespace {

constexpr int kSide = 2 * kPatternRadius + 1;

// A test's outcomes with their mean and standard deviation.
struct TestOutcomes {
  std::vector<uint64_t> bits;
  double mean = 0.0;
  double stddev = 0.0;
};

TestOutcomes Outcomes(const OrientedPatches& patches, const PatternTest& test) {
  TestOutcomes t;
  t.bits = patches.TestBits(test);
  int ones = 0;
  for (uint64_t w : t.bits) ones += std::popcount(w);
  t.mean = static_cast<double>(ones) / patches.size();
  t.stddev = std::sqrt(t.mean * (1.0 - t.mean));
  return t;
}

// Patches where both tests are 1: the hot loop of the greedy search.
DLSLAM_POPCNT_CLONES
int CountBoth(const uint64_t* a, const uint64_t* b, size_t n_words) {
  int both = 0;
  for (size_t w = 0; w < n_words; ++w) both += __builtin_popcountll(a[w] & b[w]);
  return both;
}

// Pearson correlation of two binary tests; 0 when one of them is constant.
double Correlation(const TestOutcomes& a, const TestOutcomes& b, int n) {
  if (a.stddev == 0.0 || b.stddev == 0.0) return 0.0;
  const int both = CountBoth(a.bits.data(), b.bits.data(), a.bits.size());
  return (static_cast<double>(both) / n - a.mean * b.mean) / (a.stddev * b.stddev);
}

PatternTest MakeTest(const cv::Point& p, const cv::Point& q) {
  return {static_cast<int8_t>(p.x), static_cast<int8_t>(p.y), static_cast<int8_t>(q.x),
          static_cast<int8_t>(q.y)};
}

}  // namespace

OrientedPatches::OrientedPatches() {
  for (int y = -kPatternRadius; y <= kPatternRadius; ++y) {
    for (int x = -kPatternRadius; x <= kPatternRadius; ++x) {
      if (x * x + y * y <= kPatternRadius * kPatternRadius) points_.emplace_back(x, y);
    }
  }
  values_.resize(points_.size());
}

int OrientedPatches::PointIndex(int x, int y) const {
  if (x * x + y * y > kPatternRadius * kPatternRadius) return -1;
  // points_ is sorted by (y, x): binary search instead of a second table.
  const auto it = std::lower_bound(points_.begin(), points_.end(), cv::Point(x, y),
                                   [](const cv::Point& a, const cv::Point& b) {
                                     return a.y != b.y ? a.y < b.y : a.x < b.x;
                                   });
  return static_cast<int>(it - points_.begin());
}

void OrientedPatches::Add(const cv::Mat& smoothed, int x, int y, float angle_deg) {
  DLSLAM_CHECK(smoothed.type() == CV_8UC1 && x >= kPatchRadius && y >= kPatchRadius &&
                   x < smoothed.cols - kPatchRadius && y < smoothed.rows - kPatchRadius,
               "patch at ({}, {}) leaves the {}x{} image", x, y, smoothed.cols, smoothed.rows);
  const TestRotation rotation(angle_deg);
  for (size_t i = 0; i < points_.size(); ++i) {
    const cv::Point d = RotateTestPoint(static_cast<float>(points_[i].x),
                                        static_cast<float>(points_[i].y), rotation);
    values_[i].push_back(smoothed.at<uchar>(y + d.y, x + d.x));
  }
  ++n_patches_;
}

std::vector<uint64_t> OrientedPatches::TestBits(const PatternTest& test) const {
  const int i1 = PointIndex(test.x1, test.y1), i2 = PointIndex(test.x2, test.y2);
  DLSLAM_CHECK(i1 >= 0 && i2 >= 0, "test ({}, {}) - ({}, {}) leaves the disc of radius {}",
               test.x1, test.y1, test.x2, test.y2, kPatternRadius);
  const uchar* a = values_[static_cast<size_t>(i1)].data();
  const uchar* b = values_[static_cast<size_t>(i2)].data();
  std::vector<uint64_t> bits(static_cast<size_t>((n_patches_ + 63) / 64), 0);
  for (int k = 0; k < n_patches_; ++k) {
    bits[static_cast<size_t>(k / 64)] |= static_cast<uint64_t>(a[k] < b[k]) << (k % 64);
  }
  return bits;
}

void PatternLearningOptions::Check() const {
  DLSLAM_CHECK_GE(candidate_tests, 0, "PatternLearningOptions::candidate_tests");
  DLSLAM_CHECK(min_separation >= 1 && min_separation <= kSide - 1,
               "PatternLearningOptions::min_separation {} outside [1, {}]", min_separation,
               kSide - 1);
  DLSLAM_CHECK(initial_correlation > 0.0 && initial_correlation <= 1.0,
               "PatternLearningOptions::initial_correlation {} outside (0, 1]",
               initial_correlation);
  DLSLAM_CHECK(correlation_step > 0.0 && correlation_step <= 1.0,
               "PatternLearningOptions::correlation_step {} outside (0, 1]", correlation_step);
}

LearnedPattern LearnPattern(const OrientedPatches& patches, const PatternLearningOptions& options) {
  options.Check();
  DLSLAM_CHECK_GE(patches.size(), 2 * kPatternTests, "too few patches to learn a pattern from");
  const std::vector<cv::Point>& points = patches.points();

  // Every allowed pair, then a random subset of them.
  std::vector<PatternTest> candidates;
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = i + 1; j < points.size(); ++j) {
      const cv::Point d = points[i] - points[j];
      if (std::max(std::abs(d.x), std::abs(d.y)) >= options.min_separation) {
        candidates.push_back(MakeTest(points[i], points[j]));
      }
    }
  }
  std::mt19937 rng(options.seed);
  if (options.candidate_tests > 0 &&
      static_cast<size_t>(options.candidate_tests) < candidates.size()) {
    for (size_t i = 0; i < static_cast<size_t>(options.candidate_tests); ++i) {
      std::uniform_int_distribution<size_t> pick(i, candidates.size() - 1);
      std::swap(candidates[i], candidates[pick(rng)]);
    }
    candidates.resize(static_cast<size_t>(options.candidate_tests));
  }

  // Order by distance of the mean from 0.5 (high variance first).
  std::vector<double> bias(candidates.size());
  for (size_t c = 0; c < candidates.size(); ++c) {
    bias[c] = std::abs(Outcomes(patches, candidates[c]).mean - 0.5);
  }
  std::vector<size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return bias[a] < bias[b]; });

  LearnedPattern result;
  result.candidates = static_cast<int>(candidates.size());
  for (double threshold = options.initial_correlation;;
       threshold = std::min(1.0, threshold + options.correlation_step)) {
    std::vector<TestOutcomes> picked;
    result.tests.clear();
    for (size_t c : order) {
      if (bias[c] >= 0.5) break;  // constant tests carry no information
      TestOutcomes t = Outcomes(patches, candidates[c]);
      const bool independent = std::none_of(picked.begin(), picked.end(), [&](const TestOutcomes& p) {
        return std::abs(Correlation(t, p, patches.size())) > threshold;
      });
      if (!independent) continue;
      picked.push_back(std::move(t));
      result.tests.push_back(candidates[c]);
      if (result.tests.size() == static_cast<size_t>(kPatternTests)) {
        result.correlation_threshold = threshold;
        return result;
      }
    }
    DLSLAM_CHECK_LT(threshold, 1.0, "only {} independent tests among {} candidates",
                    result.tests.size(), candidates.size());
  }
}

PatternStatistics EvaluatePattern(const OrientedPatches& patches,
                                  std::span<const PatternTest> pattern) {
  DLSLAM_CHECK(patches.size() > 0 && !pattern.empty(), "no patches or no tests to evaluate");
  std::vector<TestOutcomes> outcomes;
  PatternStatistics s;
  for (const PatternTest& t : pattern) {
    outcomes.push_back(Outcomes(patches, t));
    s.mean_bit += outcomes.back().mean;
    s.mean_abs_bias += std::abs(outcomes.back().mean - 0.5);
  }
  s.mean_bit /= static_cast<double>(pattern.size());
  s.mean_abs_bias /= static_cast<double>(pattern.size());
  double sum = 0.0;
  int pairs = 0;
  for (size_t i = 0; i < outcomes.size(); ++i) {
    for (size_t j = i + 1; j < outcomes.size(); ++j) {
      const double c = std::abs(Correlation(outcomes[i], outcomes[j], patches.size()));
      sum += c;
      s.max_abs_correlation = std::max(s.max_abs_correlation, c);
      ++pairs;
    }
  }
  s.mean_abs_correlation = pairs > 0 ? sum / pairs : 0.0;
  return s;
}

}  // namespace dlslam::features

#include "dlslam/features/matching.h"

#include <limits>

#include "dlslam/util/check.h"
#include "dlslam/util/cpu_dispatch.h"

namespace dlslam::features {
namespace {

void CheckDescriptors(const cv::Mat& d, const char* which) {
  DLSLAM_CHECK(d.empty() || (d.type() == CV_8UC1 && d.cols == kDescriptorBytes),
               "{} descriptors must be CV_8UC1 n x {}, got {} {}x{}", which, kDescriptorBytes,
               cv::typeToString(d.type()), d.rows, d.cols);
}

struct Nearest {
  int index = -1;
  int best = std::numeric_limits<int>::max();
  int second = std::numeric_limits<int>::max();
};

// The hot loop.
DLSLAM_POPCNT_CLONES
Nearest FindNearest(const uchar* descriptor, const cv::Mat& candidates) {
  Nearest n;
  for (int j = 0; j < candidates.rows; ++j) {
    const int d = detail::HammingDistanceInline(descriptor, candidates.ptr<uchar>(j));
    if (d < n.best) {
      n.second = n.best;
      n.best = d;
      n.index = j;
    } else if (d < n.second) {
      n.second = d;
    }
  }
  return n;
}

}  // namespace

DLSLAM_POPCNT_CLONES
int HammingDistance(const uchar* a, const uchar* b) { return detail::HammingDistanceInline(a, b); }

void MatchOptions::Check() const {
  DLSLAM_CHECK(ratio > 0.0 && ratio <= 1.0, "MatchOptions::ratio {} outside (0, 1]", ratio);
  DLSLAM_CHECK(max_distance >= 0 && max_distance <= 8 * kDescriptorBytes,
               "MatchOptions::max_distance {} outside [0, {}]", max_distance,
               8 * kDescriptorBytes);
}

std::vector<cv::DMatch> MatchBruteForce(const cv::Mat& query, const cv::Mat& train,
                                        const MatchOptions& options) {
  options.Check();
  CheckDescriptors(query, "query");
  CheckDescriptors(train, "train");
  std::vector<cv::DMatch> matches;
  if (query.empty() || train.empty()) return matches;
  for (int i = 0; i < query.rows; ++i) {
    const Nearest n = FindNearest(query.ptr<uchar>(i), train);
    if (n.best > options.max_distance) continue;
    // With a single train row there is no second best: the ratio test passes.
    const bool ambiguous = options.ratio < 1.0 && n.second != std::numeric_limits<int>::max() &&
                           n.best >= options.ratio * n.second;
    if (ambiguous) continue;
    if (options.mutual && FindNearest(train.ptr<uchar>(n.index), query).index != i) continue;
    matches.emplace_back(i, n.index, static_cast<float>(n.best));
  }
  return matches;
}

}  // namespace dlslam::features

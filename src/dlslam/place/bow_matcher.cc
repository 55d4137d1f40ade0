#include "dlslam/place/bow_matcher.h"

#include "dlslam/match/rotation_histogram.h"
#include "dlslam/util/check.h"

namespace dlslam::place {

void BowMatchOptions::Check() const {
  DLSLAM_CHECK(max_distance >= 0 && max_distance <= 256, "max_distance {} outside 0..256", max_distance);
  DLSLAM_CHECK(ratio > 0 && ratio <= 1, "ratio {} outside (0, 1]", ratio);
}

std::vector<MapPointId> MatchByBow(const Frame& frame, const FeatureVector& frame_features,
                                   const Frame& keyframe_frame, const FeatureVector& keyframe_features,
                                   const std::vector<MapPointId>& keyframe_points, const BowMatchOptions& options) {
  options.Check();
  DLSLAM_CHECK_EQ(keyframe_points.size(), keyframe_frame.size());
  std::vector<MapPointId> matches(frame.size(), kNoId);
  std::vector<int> distance(frame.size(), 257);
  std::vector<int> owner(frame.size(), -1);  // keyframe keypoint of each match
  // Both vectors are sorted by node: walk them together.
  auto f = frame_features.begin();
  auto k = keyframe_features.begin();
  while (f != frame_features.end() && k != keyframe_features.end()) {
    if (f->node < k->node) {
      ++f;
      continue;
    }
    if (k->node < f->node) {
      ++k;
      continue;
    }
    for (std::uint32_t kk : k->features) {
      DLSLAM_CHECK_LT(kk, keyframe_frame.size(), "keyframe feature index");
      if (keyframe_points[kk] == kNoId) continue;
      int best = 257, second = 257, best_index = -1;
      for (std::uint32_t i : f->features) {
        DLSLAM_CHECK_LT(i, frame.size(), "frame feature index");
        const int d = HammingDistance(keyframe_frame.descriptor(kk), frame.descriptor(i));
        if (d < best) {
          second = best;
          best = d;
          best_index = static_cast<int>(i);
        } else if (d < second) {
          second = d;
        }
      }
      if (best_index < 0 || best > options.max_distance) continue;
      if (second <= 256 && best > options.ratio * second) continue;
      if (best >= distance[best_index]) continue;  // the keypoint already has a closer match
      matches[best_index] = keyframe_points[kk];
      distance[best_index] = best;
      owner[best_index] = static_cast<int>(kk);
    }
    ++f;
    ++k;
  }
  if (!options.check_rotation) return matches;
  std::vector<int> matched;
  std::vector<int> bins;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (matches[i] == kNoId) continue;
    matched.push_back(static_cast<int>(i));
    bins.push_back(RotationBin(keyframe_frame.keypoint(owner[i]).angle, frame.keypoint(i).angle));
  }
  const std::vector<bool> keep = InDominantRotationBins(bins);
  for (std::size_t m = 0; m < matched.size(); ++m) {
    if (!keep[m]) matches[matched[m]] = kNoId;
  }
  return matches;
}

}  // namespace dlslam::place

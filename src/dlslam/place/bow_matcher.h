#pragma once
// Matching a frame's keypoints to a keyframe's map points through the
// vocabulary's direct index (ORB-SLAM's SearchByBoW, written by us): only
// features under the same tree node are compared, so a 1000 x 1000 match
// costs about 1000 x 10 distances instead of 10^6.

#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map_types.h"
#include "dlslam/place/bow_vector.h"

namespace dlslam::place {

struct BowMatchOptions {
  // Largest Hamming distance of an accepted match [bits of 256] (ORB-SLAM's TH_LOW).
  int max_distance = 50;
  // Best / second-best distance ratio [fraction, 0..1]; 1 disables it.
  double ratio = 0.75;
  // Keep only matches whose orientation change agrees with the dominant ones.
  bool check_rotation = true;
  void Check() const;  // throws dlslam::Error with the values
};

// Per keypoint of `frame`: the map point of the keyframe keypoint it
// matches, kNoId if none. `frame_features` / `keyframe_features` are the
// direct indices of the two (KeyFrameIndex::Describe / Features);
// `keyframe_points` holds one id per keyframe keypoint (kNoId: no point).
// Each frame keypoint takes at
// most one point (the closest descriptor wins).
std::vector<MapPointId> MatchByBow(const Frame& frame, const FeatureVector& frame_features,
                                   const Frame& keyframe_frame, const FeatureVector& keyframe_features,
                                   const std::vector<MapPointId>& keyframe_points, const BowMatchOptions& options = {});

}  // namespace dlslam::place

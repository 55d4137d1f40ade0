#pragma once
// Fusion of duplicated map points across neighbouring keyframes (ORB-SLAM's
// SearchInNeighbors): the new keyframe's points are projected into its first-
// and second-order covisible neighbours and theirs into it; a projection that
// lands on a keypoint with a matching descriptor adds the observation, or,
// when that keypoint has a point of its own, merges the two (the one with
// more observations stays). The covisibility of the keyframe is then rebuilt.

#include "dlslam/map/map.h"
#include "dlslam/match/fuse_matcher.h"

namespace dlslam {

struct FusionOptions {
  // First-order neighbours (ORB-SLAM: 10 for RGB-D) and, for each, the
  // second-order ones added (ORB-SLAM: 5).
  int neighbours = 10;
  int second_neighbours = 5;
  FuseMatchOptions match;

  void Check() const;
};

struct FusionStats {
  int targets = 0;       // neighbour keyframes searched
  int fused = 0;         // observations added or points merged
};

// Fuses `keyframe` with its neighbours with an id up to its own (newer ones
// are still tracking's).
FusionStats FuseWithNeighbours(Map* map, KeyFrameId keyframe, const FusionOptions& options = {});

}  // namespace dlslam

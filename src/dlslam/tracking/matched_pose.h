#pragma once
// The pose of a frame from its keypoints matched to map points, shared by
// tracking and relocalization.

#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map_types.h"
#include "dlslam/optimize/pose_optimizer.h"

namespace dlslam {

// Optimises `pose` on the matches (`matches[i]`: point of keypoint i, or
// kNoId) whose points are among `points`; matches to other points and
// outliers are set to kNoId. Returns the inlier count; with fewer than 3
// the pose is left unchanged and 0 is returned.
int OptimizeAndPrune(const Frame& frame, const std::vector<MapPointView>& points, const PoseOptimizerOptions& options,
                     SE3d* pose, std::vector<MapPointId>* matches);

// Drops the matches whose point projects further than `max_px` (times the
// keypoint's pyramid scale) from its keypoint at `pose`, or behind it.
void KeepMatchesNear(const Frame& frame, const std::vector<MapPointView>& points, const SE3d& pose, double max_px,
                     std::vector<MapPointId>* matches);

int CountMatches(const std::vector<MapPointId>& matches);
std::vector<MapPointId> MatchedIds(const std::vector<MapPointId>& matches);

}  // namespace dlslam

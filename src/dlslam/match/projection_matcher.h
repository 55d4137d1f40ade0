#pragma once
// Matching map points to a frame's keypoints by projecting them with a pose
// guess and comparing descriptors among the keypoints near the projection
// (ORB-SLAM's SearchByProjection), and descriptor matching between a frame
// and a keyframe when no pose guess is good enough.

#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map_types.h"

namespace dlslam {

struct ProjectionMatchOptions {
  // Search radius [px] at pyramid level 0; multiplied by the level's scale.
  double radius = 15.0;
  // Largest Hamming distance of an accepted match (ORB-SLAM's TH_HIGH).
  int max_distance = 100;
  // Best / second-best distance ratio; 1 disables the test. Applied only when
  // both candidates are on the same pyramid level.
  double ratio = 0.8;
  // Largest angle between the viewing ray and the point's mean viewing
  // direction [deg]; beyond it the descriptor is unlikely to match.
  double max_view_angle_deg = 60.0;
  // Search only levels [predicted - 1, predicted + 1] (false: any level).
  bool use_predicted_octave = true;

  void Check() const;
};

struct ProjectionMatchStats {
  int projected = 0;  // points inside the image and their distance range
  int matched = 0;
  std::vector<MapPointId> visible;  // ids of the projected points
};

// For every point not yet matched (matches[i] == kNoId for the keypoint that
// would take it), finds the best keypoint near its projection and writes the
// point id into `matches` (one entry per keypoint, resized if empty).
// Keypoints that already hold a point are not candidates.
ProjectionMatchStats SearchByProjection(const Frame& frame, const SE3d& cam_from_world,
                                        const std::vector<MapPointView>& points,
                                        const ProjectionMatchOptions& options,
                                        std::vector<MapPointId>* matches);

// Descriptor matching of the frame's keypoints against those of a keyframe
// that hold points: nearest neighbour with ratio test and orientation check.
// Returns per frame keypoint the point id (kNoId if none).
std::vector<MapPointId> MatchToKeyFrame(const Frame& frame, const Frame& keyframe_frame,
                                        const std::vector<MapPointId>& keyframe_points, int max_distance = 50,
                                        double ratio = 0.7);

}  // namespace dlslam

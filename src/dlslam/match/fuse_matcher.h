#pragma once
// Projection of map points into a keyframe to find duplicates (ORB-SLAM's
// Fuse): a point that projects onto a keypoint with a matching descriptor
// and a small reprojection error is the same landmark as that keypoint's
// point, or a new observation of it.

#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map_types.h"

namespace dlslam {

struct FuseMatchOptions {
  // Search radius [px at level 0, times the predicted level's scale].
  double radius = 3.0;
  // Largest Hamming distance of a match (ORB-SLAM's TH_LOW).
  int max_distance = 50;
  // Reprojection gates (95 %, 2 and 3 dof) in units of the keypoint's sigma^2.
  double chi2_mono = 5.991;
  double chi2_stereo = 7.815;
  // Largest angle between viewing ray and the point's mean viewing direction [deg].
  double max_view_angle_deg = 60.0;

  void Check() const;
};

struct FuseCandidate {
  MapPointId point = kNoId;
  int keypoint = -1;  // in the keyframe; it may already hold another point
};

// Candidates for every point of `points` that the keyframe does not see yet
// (`keyframe_points`: its point per keypoint).
std::vector<FuseCandidate> SearchForFusion(const Frame& frame, const SE3d& cam_from_world,
                                           const std::vector<MapPointId>& keyframe_points,
                                           const std::vector<MapPointView>& points,
                                           const FuseMatchOptions& options = {});

}  // namespace dlslam

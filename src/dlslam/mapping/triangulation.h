#pragma once
// New map points by triangulation between the new keyframe and its best
// covisible neighbours (ORB-SLAM's CreateNewMapPoints, RGB-D case): points
// for the keypoints that depth alone did not give one, chiefly far ones
// (beyond the sensor's range) and those on depth holes.

#include <optional>

#include "dlslam/map/map.h"
#include "dlslam/match/triangulation_matcher.h"

namespace dlslam {

struct TriangulationOptions {
  // Neighbours (best covisible keyframes) to triangulate with (ORB-SLAM: 10 for RGB-D).
  int neighbours = 10;
  // Pairs of keyframes closer than this [m] are skipped; <= 0: the RGB-D
  // virtual stereo baseline bf / fx (as ORB-SLAM for stereo and RGB-D).
  double min_baseline = 0.0;
  // Rays whose angle has a cosine above this carry no depth information
  // without a depth measurement (ORB-SLAM: 0.9998, about 1.1 deg).
  double max_cos_parallax = 0.9998;
  // Reprojection gates (95 %, 2 and 3 dof) in units of the keypoint's sigma^2.
  double chi2_mono = 5.991;
  double chi2_stereo = 7.815;
  // The distance ratio of the point to the two cameras must agree with the
  // ratio of the keypoints' pyramid scales within this factor times the
  // scale factor (ORB-SLAM: 1.5).
  double scale_consistency = 1.5;
  TriangulationMatchOptions match;

  void Check() const;
};

// The 3D point (world) of keypoint i1 of frame1 and i2 of frame2, or nothing
// when it fails a check: linear (DLT) triangulation when the rays' parallax
// beats that of the keypoints' depth, else the depth measurement of the
// better keypoint; then positive depth in both, reprojection error, scale
// consistency.
std::optional<Eigen::Vector3d> TriangulateMatch(const Frame& frame1, const SE3d& cam1_from_world, int i1,
                                                const Frame& frame2, const SE3d& cam2_from_world, int i2,
                                                const TriangulationOptions& options = {});

// Triangulates new points for `keyframe` with its neighbours (those with an
// id up to its own: newer ones are still tracking's). Returns how many.
int CreateNewMapPoints(Map* map, KeyFrameId keyframe, const TriangulationOptions& options = {});

}  // namespace dlslam

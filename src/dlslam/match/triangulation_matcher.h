#pragma once
// Matching between two keyframes for new points by triangulation (ORB-SLAM's
// SearchForTriangulation, with a brute-force search in place of its
// bag-of-words pre-selection): keypoints that hold no point yet are paired
// by descriptor, and a pair is kept only if the second keypoint lies on the
// epipolar line of the first (and, without depth on either side, not next to
// the epipole, where the line says nothing).

#include <utility>
#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map_types.h"

namespace dlslam {

struct TriangulationMatchOptions {
  // Largest Hamming distance of a match (ORB-SLAM's TH_LOW).
  int max_distance = 50;
  // Squared distance to the epipolar line, in units of the second keypoint's
  // pyramid sigma^2 (chi-square, 1 dof, 95 %).
  double epipolar_chi2 = 3.84;
  // Without depth, a keypoint closer than this to the epipole [px at level 0,
  // times the level's scale] is skipped.
  double min_epipole_distance = 10.0;
  // Keep only matches in the dominant bins of orientation change.
  bool check_orientation = true;

  void Check() const;
};

// Pairs (keypoint of frame1, keypoint of frame2) of keypoints with no point
// (points[i] == kNoId), each keypoint in at most one pair.
std::vector<std::pair<int, int>> SearchForTriangulation(const Frame& frame1, const SE3d& cam1_from_world,
                                                        const std::vector<MapPointId>& points1,
                                                        const Frame& frame2, const SE3d& cam2_from_world,
                                                        const std::vector<MapPointId>& points2,
                                                        const TriangulationMatchOptions& options = {});

// Fundamental matrix mapping undistorted pixels of camera 1 to epipolar
// lines of camera 2: x2^T F x1 = 0.
Eigen::Matrix3d FundamentalMatrix(const CameraIntrinsics& camera1, const SE3d& cam1_from_world,
                                  const CameraIntrinsics& camera2, const SE3d& cam2_from_world);

}  // namespace dlslam

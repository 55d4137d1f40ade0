#include "dlslam/match/triangulation_matcher.h"

#include <cmath>

#include "dlslam/match/rotation_histogram.h"
#include "dlslam/util/check.h"

namespace dlslam {

void TriangulationMatchOptions::Check() const {
  DLSLAM_CHECK(max_distance > 0 && max_distance <= 256, "max_distance {} outside (0, 256]", max_distance);
  DLSLAM_CHECK_GT(epipolar_chi2, 0.0);
  DLSLAM_CHECK_GE(min_epipole_distance, 0.0);
}

namespace {

Eigen::Matrix3d Intrinsics(const CameraIntrinsics& c) {
  Eigen::Matrix3d k;
  k << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1;
  return k;
}

}  // namespace

Eigen::Matrix3d FundamentalMatrix(const CameraIntrinsics& camera1, const SE3d& cam1_from_world,
                                  const CameraIntrinsics& camera2, const SE3d& cam2_from_world) {
  const SE3d cam2_from_cam1 = cam2_from_world * cam1_from_world.Inverse();
  const Eigen::Matrix3d essential = SO3d::Hat(cam2_from_cam1.translation()) * cam2_from_cam1.rotationMatrix();
  return Intrinsics(camera2).inverse().transpose() * essential * Intrinsics(camera1).inverse();
}

std::vector<std::pair<int, int>> SearchForTriangulation(const Frame& frame1, const SE3d& cam1_from_world,
                                                        const std::vector<MapPointId>& points1,
                                                        const Frame& frame2, const SE3d& cam2_from_world,
                                                        const std::vector<MapPointId>& points2,
                                                        const TriangulationMatchOptions& options) {
  options.Check();
  DLSLAM_CHECK_EQ(points1.size(), frame1.size());
  DLSLAM_CHECK_EQ(points2.size(), frame2.size());
  const Eigen::Matrix3d f21 = FundamentalMatrix(frame1.camera(), cam1_from_world, frame2.camera(), cam2_from_world);
  // Epipole in image 2: the projection of camera 1's centre.
  const Eigen::Vector3d centre1_in_2 = cam2_from_world * cam1_from_world.Inverse().translation();
  const bool epipole_in_front = centre1_in_2.z() > 0;
  const Eigen::Vector2d epipole = epipole_in_front ? frame2.camera().Project(centre1_in_2) : Eigen::Vector2d::Zero();

  std::vector<int> candidates2;
  for (std::size_t j = 0; j < frame2.size(); ++j) {
    if (points2[j] == kNoId) candidates2.push_back(static_cast<int>(j));
  }
  const ScalePyramid& pyr2 = frame2.pyramid();
  std::vector<int> owner(frame2.size(), -1);  // frame2 keypoint -> frame1 keypoint
  std::vector<int> owner_distance(frame2.size(), 257);
  for (std::size_t i = 0; i < frame1.size(); ++i) {
    if (points1[i] != kNoId) continue;
    const FrameKeypoint& k1 = frame1.keypoint(i);
    const Eigen::Vector3d line = f21 * Eigen::Vector3d(k1.uv.x(), k1.uv.y(), 1.0);
    const double line_norm2 = line.head<2>().squaredNorm();
    if (line_norm2 < 1e-18) continue;
    int best = options.max_distance + 1, best_j = -1;
    for (int j : candidates2) {
      const int d = HammingDistance(frame1.descriptor(i), frame2.descriptor(j));
      if (d >= best) continue;
      const FrameKeypoint& k2 = frame2.keypoint(j);
      if (k1.right_u < 0 && k2.right_u < 0 && epipole_in_front &&
          (k2.uv - epipole).norm() < options.min_epipole_distance * pyr2.Scale(k2.octave)) {
        continue;
      }
      const double along = line.x() * k2.uv.x() + line.y() * k2.uv.y() + line.z();
      if (along * along / line_norm2 > options.epipolar_chi2 * pyr2.Scale(k2.octave) * pyr2.Scale(k2.octave)) continue;
      best = d;
      best_j = j;
    }
    if (best_j < 0 || best >= owner_distance[best_j]) continue;
    owner[best_j] = static_cast<int>(i);
    owner_distance[best_j] = best;
  }
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> bins;
  for (std::size_t j = 0; j < frame2.size(); ++j) {
    if (owner[j] < 0) continue;
    pairs.emplace_back(owner[j], static_cast<int>(j));
    bins.push_back(RotationBin(frame1.keypoint(owner[j]).angle, frame2.keypoint(j).angle));
  }
  if (!options.check_orientation) return pairs;
  const std::vector<bool> keep = InDominantRotationBins(bins);
  std::vector<std::pair<int, int>> kept;
  for (std::size_t m = 0; m < pairs.size(); ++m) {
    if (keep[m]) kept.push_back(pairs[m]);
  }
  return kept;
}

}  // namespace dlslam

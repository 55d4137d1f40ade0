#include "dlslam/match/projection_matcher.h"

#include "dlslam/match/point_visibility.h"

#include <algorithm>
#include <cmath>

#include "dlslam/match/rotation_histogram.h"
#include "dlslam/util/check.h"

namespace dlslam {

void ProjectionMatchOptions::Check() const {
  DLSLAM_CHECK_GT(radius, 0.0);
  DLSLAM_CHECK(max_distance > 0 && max_distance <= 256, "max_distance {} outside (0, 256]", max_distance);
  DLSLAM_CHECK(ratio > 0 && ratio <= 1, "ratio {} outside (0, 1]", ratio);
  DLSLAM_CHECK(max_view_angle_deg > 0 && max_view_angle_deg <= 180);
}

ProjectionMatchStats SearchByProjection(const Frame& frame, const SE3d& cam_from_world,
                                        const std::vector<MapPointView>& points,
                                        const ProjectionMatchOptions& options,
                                        std::vector<MapPointId>* matches) {
  options.Check();
  if (matches->empty()) matches->assign(frame.size(), kNoId);
  DLSLAM_CHECK_EQ(matches->size(), frame.size());
  const CameraIntrinsics& cam = frame.camera();
  const ScalePyramid& pyr = frame.pyramid();
  const PointVisibility visibility(cam, cam_from_world, options.max_view_angle_deg);
  // Best candidate per keypoint, so two points never take the same keypoint.
  std::vector<int> best_distance(frame.size(), 256);
  ProjectionMatchStats stats;
  std::vector<int> candidates;
  for (const MapPointView& p : points) {
    const std::optional<VisibleProjection> seen = visibility.Project(p);
    if (!seen) continue;
    const Eigen::Vector3d& pc = seen->point_cam;
    const Eigen::Vector2d& uv = seen->uv;
    const double dist = seen->distance;
    ++stats.projected;
    stats.visible.push_back(p.id);
    const int octave = PredictOctave(dist, p.max_distance, pyr);
    const double radius = options.radius * pyr.Scale(octave);
    const int lo = options.use_predicted_octave ? octave - 1 : -1;
    const int hi = options.use_predicted_octave ? octave + 1 : -1;
    const double right_u = uv.x() - cam.bf / pc.z();
    int best = 256, second = 256, best_idx = -1, best_octave = -1, second_octave = -1;
    frame.FeaturesInArea(uv.x(), uv.y(), radius, std::max(lo, 0), hi, candidates);
    for (int idx : candidates) {
      if ((*matches)[idx] != kNoId && best_distance[idx] == 256) continue;  // taken before this search
      const FrameKeypoint& k = frame.keypoint(idx);
      if (k.right_u >= 0 && std::abs(right_u - k.right_u) > radius) continue;
      const int d = HammingDistance(p.descriptor.data(), frame.descriptor(idx));
      if (d < best) {
        second = best;
        second_octave = best_octave;
        best = d;
        best_idx = idx;
        best_octave = k.octave;
      } else if (d < second) {
        second = d;
        second_octave = k.octave;
      }
    }
    if (best_idx < 0 || best > options.max_distance) continue;
    if (best_octave == second_octave && best > options.ratio * second) continue;
    if (best >= best_distance[best_idx]) continue;
    if ((*matches)[best_idx] == kNoId) ++stats.matched;
    (*matches)[best_idx] = p.id;
    best_distance[best_idx] = best;
  }
  return stats;
}

std::vector<MapPointId> MatchToKeyFrame(const Frame& frame, const Frame& keyframe_frame,
                                        const std::vector<MapPointId>& keyframe_points, int max_distance,
                                        double ratio) {
  DLSLAM_CHECK_EQ(keyframe_points.size(), keyframe_frame.size());
  std::vector<MapPointId> matches(frame.size(), kNoId);
  std::vector<int> taken_distance(frame.size(), 256);
  std::vector<std::pair<int, int>> binned;
  std::vector<int> owner(frame.size(), -1);
  for (std::size_t k = 0; k < keyframe_frame.size(); ++k) {
    if (keyframe_points[k] == kNoId) continue;
    int best = 256, second = 256, best_idx = -1;
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const int d = HammingDistance(keyframe_frame.descriptor(k), frame.descriptor(i));
      if (d < best) {
        second = best;
        best = d;
        best_idx = static_cast<int>(i);
      } else if (d < second) {
        second = d;
      }
    }
    if (best_idx < 0 || best > max_distance || best > ratio * second) continue;
    if (best >= taken_distance[best_idx]) continue;
    matches[best_idx] = keyframe_points[k];
    taken_distance[best_idx] = best;
    owner[best_idx] = static_cast<int>(k);
  }
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (matches[i] == kNoId) continue;
    binned.emplace_back(static_cast<int>(i),
                        RotationBin(keyframe_frame.keypoint(owner[i]).angle, frame.keypoint(i).angle));
  }
  std::vector<int> bins;
  for (const auto& [idx, bin] : binned) bins.push_back(bin);
  const std::vector<bool> keep = InDominantRotationBins(bins);
  for (std::size_t m = 0; m < binned.size(); ++m) {
    if (!keep[m]) matches[binned[m].first] = kNoId;
  }
  return matches;
}

}  // namespace dlslam

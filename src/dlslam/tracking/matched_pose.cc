#include "dlslam/tracking/matched_pose.h"

#include <algorithm>
#include <unordered_map>

namespace dlslam {
namespace {

std::unordered_map<MapPointId, const MapPointView*> IndexById(const std::vector<MapPointView>& points) {
  std::unordered_map<MapPointId, const MapPointView*> by_id;
  for (const MapPointView& p : points) by_id[p.id] = &p;
  return by_id;
}

}  // namespace

int CountMatches(const std::vector<MapPointId>& matches) {
  return static_cast<int>(std::count_if(matches.begin(), matches.end(), [](MapPointId id) { return id != kNoId; }));
}

std::vector<MapPointId> MatchedIds(const std::vector<MapPointId>& matches) {
  std::vector<MapPointId> ids;
  for (MapPointId id : matches) {
    if (id != kNoId) ids.push_back(id);
  }
  return ids;
}

void KeepMatchesNear(const Frame& frame, const std::vector<MapPointView>& points, const SE3d& pose, double max_px,
                     std::vector<MapPointId>* matches) {
  const auto by_id = IndexById(points);
  for (std::size_t i = 0; i < matches->size(); ++i) {
    if ((*matches)[i] == kNoId) continue;
    const auto it = by_id.find((*matches)[i]);
    const Eigen::Vector3d p = it == by_id.end() ? Eigen::Vector3d::Zero() : pose * it->second->position;
    const FrameKeypoint& k = frame.keypoint(i);
    const double reach = max_px * frame.pyramid().Scale(k.octave);
    if (p.z() <= 1e-6 || (frame.camera().Project(p) - k.uv).squaredNorm() > reach * reach) (*matches)[i] = kNoId;
  }
}

int OptimizeAndPrune(const Frame& frame, const std::vector<MapPointView>& points, const PoseOptimizerOptions& options,
                     SE3d* pose, std::vector<MapPointId>* matches) {
  const auto by_id = IndexById(points);
  std::vector<PoseObservation> observations;
  std::vector<int> keypoint_of;
  for (std::size_t i = 0; i < matches->size(); ++i) {
    const auto it = by_id.find((*matches)[i]);
    if (it == by_id.end()) {
      (*matches)[i] = kNoId;
      continue;
    }
    const FrameKeypoint& k = frame.keypoint(i);
    PoseObservation o;
    o.point_world = it->second->position;
    o.pixel = k.uv;
    o.right_u = k.right_u;
    o.information = frame.pyramid().InverseSigma2(k.octave);
    observations.push_back(o);
    keypoint_of.push_back(static_cast<int>(i));
  }
  const PoseOptimizationResult r = OptimizePose(frame.camera(), *pose, observations, options);
  if (r.num_inliers < 3) return 0;
  *pose = r.cam_from_world;
  for (std::size_t j = 0; j < observations.size(); ++j) {
    if (!r.inliers[j]) (*matches)[keypoint_of[j]] = kNoId;
  }
  return r.num_inliers;
}

}  // namespace dlslam

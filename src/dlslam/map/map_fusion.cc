// The map operations behind new points by triangulation and the fusion of
// duplicated points across neighbouring keyframes (local mapping).

#include <algorithm>

#include "dlslam/map/map.h"
#include "dlslam/util/check.h"

namespace dlslam {

std::vector<KeyFrameId> Map::BestCovisible(KeyFrameId keyframe, std::size_t n, KeyFrameId max_id) const {
  std::lock_guard lock(mutex_);
  const auto it = keyframes_.find(keyframe);
  if (it == keyframes_.end()) return {};
  std::vector<std::pair<int, KeyFrameId>> ranked;
  for (const auto& [other, weight] : it->second.covisibility) {
    if (other <= max_id) ranked.emplace_back(weight, other);
  }
  std::sort(ranked.rbegin(), ranked.rend());
  std::vector<KeyFrameId> out;
  for (std::size_t k = 0; k < std::min(n, ranked.size()); ++k) out.push_back(ranked[k].second);
  return out;
}

MapPointId Map::AddTriangulatedPoint(const Eigen::Vector3d& position, KeyFrameId keyframe1, int keypoint1,
                                     KeyFrameId keyframe2, int keypoint2) {
  DLSLAM_CHECK_NE(keyframe1, keyframe2);
  std::lock_guard lock(mutex_);
  const auto kf1 = keyframes_.find(keyframe1);
  const auto kf2 = keyframes_.find(keyframe2);
  if (kf1 == keyframes_.end() || kf2 == keyframes_.end()) return kNoId;
  DLSLAM_CHECK(keypoint1 >= 0 && keypoint1 < static_cast<int>(kf1->second.points.size()));
  DLSLAM_CHECK(keypoint2 >= 0 && keypoint2 < static_cast<int>(kf2->second.points.size()));
  if (kf1->second.points[keypoint1] != kNoId || kf2->second.points[keypoint2] != kNoId) return kNoId;
  MapPoint p;
  p.id = next_point_id_++;
  p.position = position;
  p.observations[keyframe1] = keypoint1;
  p.observations[keyframe2] = keypoint2;
  p.reference_keyframe = keyframe1;
  p.first_keyframe = keyframe1;
  kf1->second.points[keypoint1] = p.id;
  kf2->second.points[keypoint2] = p.id;
  RefreshPoint(p);
  const MapPointId id = p.id;
  points_.emplace(id, std::move(p));
  return id;
}

bool Map::FusePoint(MapPointId point, KeyFrameId keyframe, int keypoint) {
  std::lock_guard lock(mutex_);
  const auto p_it = points_.find(point);
  const auto kf_it = keyframes_.find(keyframe);
  if (p_it == points_.end() || kf_it == keyframes_.end()) return false;
  KeyFrame& kf = kf_it->second;
  DLSLAM_CHECK(keypoint >= 0 && keypoint < static_cast<int>(kf.points.size()));
  if (p_it->second.observations.count(keyframe)) return false;
  const MapPointId existing = kf.points[keypoint];
  if (existing == kNoId) {
    kf.points[keypoint] = point;
    p_it->second.observations[keyframe] = keypoint;
    RefreshPoint(p_it->second);
    return true;
  }
  // Two points for one keypoint: the same landmark, created twice.
  const std::size_t views = p_it->second.observations.size();
  const std::size_t existing_views = points_.at(existing).observations.size();
  if (existing_views >= views) {
    ReplacePointLocked(point, existing);
  } else {
    ReplacePointLocked(existing, point);
  }
  return true;
}

void Map::ReplacePointLocked(MapPointId from, MapPointId into) {
  DLSLAM_CHECK_NE(from, into);
  MapPoint& source = points_.at(from);
  MapPoint& target = points_.at(into);
  for (const auto& [kf_id, idx] : source.observations) {
    KeyFrame& kf = keyframes_.at(kf_id);
    if (target.observations.count(kf_id)) {
      kf.points[idx] = kNoId;  // the keyframe sees `into` at another keypoint already
    } else {
      kf.points[idx] = into;
      target.observations[kf_id] = idx;
    }
  }
  target.times_visible += source.times_visible;
  target.times_found += source.times_found;
  target.first_keyframe = std::min(target.first_keyframe, source.first_keyframe);
  points_.erase(from);
  RefreshPoint(target);
}

}  // namespace dlslam

// Map::Export and Map::Import: the whole map as plain records, for map files.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "dlslam/map/map.h"
#include "dlslam/util/check.h"

namespace dlslam {

namespace {

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }
bool Finite(const SE3d& pose) {
  return pose.translation().allFinite() && pose.so3().quaternion().coeffs().allFinite();
}

[[noreturn]] void Defect(const std::string& what) { throw Error("inconsistent map: " + what); }

}  // namespace

std::vector<Eigen::Vector3d> Map::PointPositions() const {
  std::lock_guard lock(mutex_);
  std::vector<Eigen::Vector3d> out;
  out.reserve(points_.size());
  for (const auto& [id, p] : points_) out.push_back(p.position);
  return out;
}

MapContents Map::Export() const {
  std::lock_guard lock(mutex_);
  MapContents out;
  out.keyframes.reserve(keyframes_.size());
  for (const auto& [id, kf] : keyframes_) out.keyframes.push_back(kf);
  std::sort(out.keyframes.begin(), out.keyframes.end(), [](const KeyFrame& a, const KeyFrame& b) { return a.id < b.id; });
  out.points.reserve(points_.size());
  for (const auto& [id, p] : points_) out.points.push_back(p);
  std::sort(out.points.begin(), out.points.end(), [](const MapPoint& a, const MapPoint& b) { return a.id < b.id; });
  for (const auto& [id, c] : culled_) out.culled.push_back({id, c.parent, c.cam_from_parent});
  std::sort(out.culled.begin(), out.culled.end(),
            [](const CulledKeyFrame& a, const CulledKeyFrame& b) { return a.id < b.id; });
  out.anchors.assign(anchors_.begin(), anchors_.end());
  std::sort(out.anchors.begin(), out.anchors.end());
  out.next_keyframe_id = next_keyframe_id_;
  out.next_point_id = next_point_id_;
  return out;
}

void Map::Import(MapContents contents) {
  std::unordered_map<KeyFrameId, std::size_t> keyframe_index;
  std::unordered_set<KeyFrameId> culled_ids;
  for (std::size_t i = 0; i < contents.keyframes.size(); ++i) {
    const KeyFrame& kf = contents.keyframes[i];
    if (kf.id == kNoId || kf.id >= contents.next_keyframe_id) {
      Defect(fmt::format("keyframe id {} is not below the next id {}", kf.id, contents.next_keyframe_id));
    }
    if (!keyframe_index.emplace(kf.id, i).second) Defect(fmt::format("keyframe {} appears twice", kf.id));
    if (!kf.frame) Defect(fmt::format("keyframe {} has no frame", kf.id));
    if (kf.points.size() != kf.frame->size()) {
      Defect(fmt::format("keyframe {} has {} point slots for {} keypoints", kf.id, kf.points.size(), kf.frame->size()));
    }
    if (!Finite(kf.cam_from_world)) Defect(fmt::format("keyframe {} has a non-finite pose", kf.id));
  }
  for (const CulledKeyFrame& c : contents.culled) {
    if (keyframe_index.count(c.id) || !culled_ids.insert(c.id).second) {
      Defect(fmt::format("culled keyframe {} is also a keyframe, or culled twice", c.id));
    }
    if (!Finite(c.cam_from_parent)) Defect(fmt::format("culled keyframe {} has a non-finite pose", c.id));
  }
  const auto known_keyframe = [&](KeyFrameId id) { return keyframe_index.count(id) > 0; };
  for (KeyFrameId a : contents.anchors) {
    if (!known_keyframe(a)) Defect(fmt::format("anchor {} is not a keyframe", a));
  }
  for (const CulledKeyFrame& c : contents.culled) {
    if (!known_keyframe(c.parent) && !culled_ids.count(c.parent)) {
      Defect(fmt::format("culled keyframe {} has an unknown parent {}", c.id, c.parent));
    }
  }
  std::unordered_map<MapPointId, const MapPoint*> point_by_id;
  for (const MapPoint& p : contents.points) {
    if (p.id == kNoId || p.id >= contents.next_point_id) {
      Defect(fmt::format("point id {} is not below the next id {}", p.id, contents.next_point_id));
    }
    if (!point_by_id.emplace(p.id, &p).second) Defect(fmt::format("point {} appears twice", p.id));
    if (!Finite(p.position) || !Finite(p.normal) || !std::isfinite(p.min_distance) || !std::isfinite(p.max_distance)) {
      Defect(fmt::format("point {} has non-finite numbers", p.id));
    }
    if (p.observations.empty()) Defect(fmt::format("point {} has no observation", p.id));
    if (!known_keyframe(p.reference_keyframe)) {
      Defect(fmt::format("point {} has an unknown reference keyframe {}", p.id, p.reference_keyframe));
    }
    for (const auto& [kf_id, keypoint] : p.observations) {
      const auto it = keyframe_index.find(kf_id);
      if (it == keyframe_index.end()) Defect(fmt::format("point {} is observed by an unknown keyframe {}", p.id, kf_id));
      const KeyFrame& kf = contents.keyframes[it->second];
      if (keypoint < 0 || static_cast<std::size_t>(keypoint) >= kf.points.size() ||
          kf.points[static_cast<std::size_t>(keypoint)] != p.id) {
        Defect(fmt::format("point {} claims keypoint {} of keyframe {}, which does not hold it", p.id, keypoint, kf_id));
      }
    }
  }
  for (const KeyFrame& kf : contents.keyframes) {
    for (std::size_t k = 0; k < kf.points.size(); ++k) {
      if (kf.points[k] == kNoId) continue;
      const auto it = point_by_id.find(kf.points[k]);
      if (it == point_by_id.end() || !it->second->observations.count(kf.id)) {
        Defect(fmt::format("keyframe {} keypoint {} holds point {}, which does not observe it", kf.id, k, kf.points[k]));
      }
    }
    if (kf.parent != kNoId && !known_keyframe(kf.parent)) {
      Defect(fmt::format("keyframe {} has an unknown parent {}", kf.id, kf.parent));
    }
    for (const auto& [other, shared] : kf.covisibility) {
      if (!known_keyframe(other) || other == kf.id || shared <= 0) {
        Defect(fmt::format("keyframe {} has a bad covisibility edge to {} ({} shared)", kf.id, other, shared));
      }
    }
    for (KeyFrameId other : kf.loop_edges) {
      if (!known_keyframe(other)) Defect(fmt::format("keyframe {} has a loop edge to unknown {}", kf.id, other));
    }
  }
  std::lock_guard lock(mutex_);
  DLSLAM_CHECK(keyframes_.empty() && points_.empty() && culled_.empty(), "Map::Import needs an empty map");
  for (KeyFrame& kf : contents.keyframes) {
    const KeyFrameId id = kf.id;
    keyframes_.emplace(id, std::move(kf));
  }
  for (MapPoint& p : contents.points) {
    const MapPointId id = p.id;
    points_.emplace(id, std::move(p));
  }
  for (const CulledKeyFrame& c : contents.culled) culled_[c.id] = {c.parent, c.cam_from_parent};
  anchors_.insert(contents.anchors.begin(), contents.anchors.end());
  next_keyframe_id_ = contents.next_keyframe_id;
  next_point_id_ = contents.next_point_id;
  ++generation_;  // whatever a tracker remembered belongs to another map
}

}  // namespace dlslam

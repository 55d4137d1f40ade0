// The map operations that local mapping runs: local bundle adjustment cut
// out and written back, point culling and keyframe culling.

#include <algorithm>
#include <unordered_set>

#include "dlslam/map/map.h"
#include "dlslam/util/check.h"

namespace dlslam {

LocalBundle Map::BuildLocalBundle(KeyFrameId keyframe) const {
  std::lock_guard lock(mutex_);
  LocalBundle bundle;
  const KeyFrame& kf = keyframes_.at(keyframe);
  bundle.problem.camera = kf.frame->camera();
  std::unordered_map<KeyFrameId, int> pose_index;
  AddBundlePoseLocked(keyframe, false, &bundle, &pose_index);
  for (const auto& [other, w] : kf.covisibility) AddBundlePoseLocked(other, false, &bundle, &pose_index);
  const std::size_t num_local = bundle.pose_ids.size();
  std::unordered_set<MapPointId> added;
  for (std::size_t i = 0; i < num_local; ++i) {
    for (MapPointId pid : keyframes_.at(bundle.pose_ids[i]).points) {
      if (pid == kNoId || !added.insert(pid).second) continue;
      bundle.point_ids.push_back(pid);
      bundle.problem.points.push_back(points_.at(pid).position);
    }
  }
  AddBundleObservationsLocked(/*fix_new_poses=*/true, &bundle, &pose_index);
  return bundle;
}

void Map::AddBundlePoseLocked(KeyFrameId keyframe, bool fixed, LocalBundle* bundle,
                              std::unordered_map<KeyFrameId, int>* pose_index) const {
  if (pose_index->count(keyframe)) return;
  (*pose_index)[keyframe] = static_cast<int>(bundle->pose_ids.size());
  bundle->pose_ids.push_back(keyframe);
  bundle->problem.poses.push_back({keyframes_.at(keyframe).cam_from_world, fixed || IsAnchorLocked(keyframe)});
}

void Map::AddBundleObservationsLocked(bool fix_new_poses, LocalBundle* bundle,
                                      std::unordered_map<KeyFrameId, int>* pose_index) const {
  for (std::size_t j = 0; j < bundle->point_ids.size(); ++j) {
    for (const auto& [kf_id, idx] : points_.at(bundle->point_ids[j]).observations) {
      AddBundlePoseLocked(kf_id, fix_new_poses, bundle, pose_index);  // no-op for poses already in
      const KeyFrame& observer = keyframes_.at(kf_id);
      const FrameKeypoint& k = observer.frame->keypoint(idx);
      BundleProblem::Observation o;
      o.pose = pose_index->at(kf_id);
      o.point = static_cast<int>(j);
      o.pixel = k.uv;
      o.right_u = k.right_u;
      o.information = observer.frame->pyramid().InverseSigma2(k.octave);
      bundle->problem.observations.push_back(o);
      bundle->keypoints.push_back(idx);
    }
  }
}

void Map::ApplyLocalBundle(const LocalBundle& bundle, const std::vector<bool>& outlier) {
  DLSLAM_CHECK_EQ(outlier.size(), bundle.problem.observations.size());
  std::lock_guard lock(mutex_);
  ApplyBundleLocked(bundle, outlier);
}

void Map::ApplyBundleLocked(const LocalBundle& bundle, const std::vector<bool>& outlier) {
  for (std::size_t k = 0; k < outlier.size(); ++k) {
    if (!outlier[k]) continue;
    const auto& o = bundle.problem.observations[k];
    const MapPointId pid = bundle.point_ids[o.point];
    const KeyFrameId kid = bundle.pose_ids[o.pose];
    const auto p = points_.find(pid);
    if (p != points_.end() && keyframes_.count(kid) && p->second.observations.count(kid)) {
      EraseObservationLocked(pid, kid);
    }
  }
  for (std::size_t i = 0; i < bundle.pose_ids.size(); ++i) {
    if (bundle.problem.poses[i].fixed) continue;
    const auto it = keyframes_.find(bundle.pose_ids[i]);
    if (it != keyframes_.end()) it->second.cam_from_world = bundle.problem.poses[i].cam_from_world;
  }
  for (std::size_t j = 0; j < bundle.point_ids.size(); ++j) {
    const auto it = points_.find(bundle.point_ids[j]);
    if (it == points_.end()) continue;
    it->second.position = bundle.problem.points[j];
    RefreshPoint(it->second);
  }
}

int Map::CullRecentPoints(KeyFrameId current, int min_observations, double min_found_ratio) {
  std::lock_guard lock(mutex_);
  std::vector<MapPointId> doomed;
  for (const auto& [id, p] : points_) {
    if (p.first_keyframe + 3 < current) continue;  // no longer recent
    const bool rarely_found = p.times_found < min_found_ratio * p.times_visible;
    const bool few_views = current >= p.first_keyframe + 2 &&
                           static_cast<int>(p.observations.size()) < min_observations;
    if (rarely_found || few_views) doomed.push_back(id);
  }
  for (MapPointId id : doomed) ErasePointLocked(id);
  return static_cast<int>(doomed.size());
}

std::vector<KeyFrameId> Map::CullRedundantKeyFrames(KeyFrameId current, double close_depth, double redundancy,
                                                    int min_views) {
  std::lock_guard lock(mutex_);
  std::vector<KeyFrameId> culled;
  std::vector<KeyFrameId> candidates;
  for (const auto& [other, w] : keyframes_.at(current).covisibility) candidates.push_back(other);
  for (KeyFrameId id : candidates) {
    // Keyframes newer than `current` have not been through local mapping yet
    // (ids grow and the queue is FIFO). Tracking may still be inserting one:
    // it links the keyframe into the covisibility graph and then reads it
    // back, so culling it here would pull it from under the tracking thread.
    if (IsAnchorLocked(id) || id >= current || !keyframes_.count(id)) continue;
    const KeyFrame& kf = keyframes_.at(id);
    if (!kf.loop_edges.empty()) continue;  // a loop anchor: the pose graph needs it
    int close_points = 0, redundant = 0;
    for (std::size_t i = 0; i < kf.points.size(); ++i) {
      const MapPointId pid = kf.points[i];
      if (pid == kNoId) continue;
      const double z = kf.frame->keypoint(i).depth;
      if (z <= 0 || z > close_depth) continue;
      ++close_points;
      const int octave = kf.frame->keypoint(i).octave;
      int views = 0;
      for (const auto& [other, idx] : points_.at(pid).observations) {
        if (other == id) continue;
        if (keyframes_.at(other).frame->keypoint(idx).octave <= octave + 1) ++views;
        if (views >= min_views) break;
      }
      redundant += views >= min_views;
    }
    if (close_points > 0 && redundant > redundancy * close_points) {
      EraseKeyFrameLocked(id);
      culled.push_back(id);
    }
  }
  return culled;
}

std::optional<SE3d> Map::ResolveCamFromWorld(KeyFrameId keyframe) const {
  std::lock_guard lock(mutex_);
  SE3d cam_from_kf;  // accumulates along the chain of culled keyframes
  KeyFrameId id = keyframe;
  for (int guard = 0; guard < 100000; ++guard) {
    if (const auto it = keyframes_.find(id); it != keyframes_.end()) return cam_from_kf * it->second.cam_from_world;
    const auto c = culled_.find(id);
    if (c == culled_.end()) return std::nullopt;
    cam_from_kf = cam_from_kf * c->second.cam_from_parent;
    id = c->second.parent;
  }
  return std::nullopt;
}

void Map::EraseObservationLocked(MapPointId point, KeyFrameId keyframe) {
  MapPoint& p = points_.at(point);
  const int idx = p.observations.at(keyframe);
  keyframes_.at(keyframe).points[idx] = kNoId;
  p.observations.erase(keyframe);
  if (p.observations.empty()) {
    points_.erase(point);
    return;
  }
  if (p.reference_keyframe == keyframe) p.reference_keyframe = p.observations.begin()->first;
  RefreshPoint(p);
}

void Map::ErasePointLocked(MapPointId point) {
  const MapPoint& p = points_.at(point);
  for (const auto& [kf_id, idx] : p.observations) keyframes_.at(kf_id).points[idx] = kNoId;
  points_.erase(point);
}

void Map::EraseKeyFrameLocked(KeyFrameId keyframe) {
  KeyFrame& kf = keyframes_.at(keyframe);
  for (std::size_t i = 0; i < kf.points.size(); ++i) {
    if (kf.points[i] != kNoId) EraseObservationLocked(kf.points[i], keyframe);
  }
  for (const auto& [other, w] : kf.covisibility) keyframes_.at(other).covisibility.erase(keyframe);
  for (KeyFrameId other : kf.loop_edges) keyframes_.at(other).loop_edges.erase(keyframe);
  // Children move to the culled keyframe's parent (or to the strongest neighbour).
  KeyFrameId parent = kf.parent;
  if (parent == kNoId && !kf.covisibility.empty()) {
    parent = std::max_element(kf.covisibility.begin(), kf.covisibility.end(),
                              [](const auto& a, const auto& b) { return a.second < b.second; })
                 ->first;
  }
  for (auto& [id, other] : keyframes_) {
    if (other.parent == keyframe) other.parent = parent;
  }
  if (parent != kNoId) {
    culled_[keyframe] = {parent, kf.cam_from_world * keyframes_.at(parent).cam_from_world.Inverse()};
  }
  keyframes_.erase(keyframe);
}

}  // namespace dlslam

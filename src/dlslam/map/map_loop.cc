// The map operations behind loop closing: loop edges, the essential graph
// for the pose graph, writing corrected poses back (with everything that
// hangs off them), global bundle adjustment cut out and written back.

#include <algorithm>
#include <map>
#include <utility>

#include "dlslam/map/map.h"
#include "dlslam/util/check.h"

namespace dlslam {

void Map::AddLoopEdge(KeyFrameId a, KeyFrameId b) {
  std::lock_guard lock(mutex_);
  const auto ka = keyframes_.find(a);
  const auto kb = keyframes_.find(b);
  if (a == b || ka == keyframes_.end() || kb == keyframes_.end()) return;
  ka->second.loop_edges.insert(b);
  kb->second.loop_edges.insert(a);
}

EssentialGraph Map::GetEssentialGraph(int min_covisibility) const {
  std::lock_guard lock(mutex_);
  EssentialGraph graph;
  for (const auto& [id, kf] : keyframes_) graph.ids.push_back(id);
  std::sort(graph.ids.begin(), graph.ids.end());
  std::unordered_map<KeyFrameId, int> node;
  for (std::size_t i = 0; i < graph.ids.size(); ++i) {
    node[graph.ids[i]] = static_cast<int>(i);
    graph.cam_from_world.push_back(keyframes_.at(graph.ids[i]).cam_from_world);
  }
  using Kind = EssentialGraph::Edge::Kind;
  // Lower rank wins when a pair is several kinds at once.
  const auto rank = [](Kind kind) { return kind == Kind::kLoop ? 0 : kind == Kind::kTree ? 1 : 2; };
  std::map<std::pair<int, int>, Kind> pairs;  // ordered: edges come out sorted
  const auto add = [&](KeyFrameId a, KeyFrameId b, Kind kind) {
    const auto na = node.find(a);
    const auto nb = node.find(b);
    if (a == b || na == node.end() || nb == node.end()) return;
    const auto key = std::minmax(na->second, nb->second);
    const auto [it, inserted] = pairs.emplace(key, kind);
    if (!inserted && rank(kind) < rank(it->second)) it->second = kind;
  };
  for (const auto& [id, kf] : keyframes_) {
    if (kf.parent != kNoId) add(id, kf.parent, Kind::kTree);
    for (KeyFrameId other : kf.loop_edges) add(id, other, Kind::kLoop);
    for (const auto& [other, shared] : kf.covisibility) {
      if (shared >= min_covisibility) add(id, other, Kind::kCovisibility);
    }
  }
  for (const auto& [key, kind] : pairs) {
    const auto [from, to] = key;
    graph.edges.push_back({from, to, graph.cam_from_world[to] * graph.cam_from_world[from].Inverse(), kind});
  }
  return graph;
}

int Map::ApplyCorrectedPoses(const std::unordered_map<KeyFrameId, SE3d>& corrected) {
  std::lock_guard lock(mutex_);
  std::unordered_map<KeyFrameId, SE3d> old_cam_from_world;
  for (const auto& [id, kf] : keyframes_) old_cam_from_world.emplace(id, kf.cam_from_world);
  std::unordered_set<KeyFrameId> moved;
  KeyFrameId newest_corrected = 0;
  bool any = false;
  for (const auto& [id, cam_from_world] : corrected) {
    const auto it = keyframes_.find(id);
    if (it == keyframes_.end()) continue;
    any = true;
    newest_corrected = std::max(newest_corrected, id);
    if (it->second.cam_from_world.matrix() == cam_from_world.matrix()) continue;
    it->second.cam_from_world = cam_from_world;
    moved.insert(id);
  }
  if (!any) return 0;
  std::unordered_set<KeyFrameId> followers;
  for (const auto& [id, kf] : keyframes_) {
    if (id > newest_corrected) followers.insert(id);
  }
  ++generation_;
  return PropagateCorrectionLocked(old_cam_from_world, std::move(moved), followers, {});
}

LocalBundle Map::BuildGlobalBundle() const {
  std::lock_guard lock(mutex_);
  LocalBundle bundle;
  if (keyframes_.empty()) return bundle;
  bundle.problem.camera = keyframes_.begin()->second.frame->camera();
  // Points in id order so that the bundle does not depend on hash order.
  for (const auto& [id, p] : points_) {
    if (p.observations.size() >= 2) bundle.point_ids.push_back(id);
  }
  std::sort(bundle.point_ids.begin(), bundle.point_ids.end());
  for (MapPointId id : bundle.point_ids) bundle.problem.points.push_back(points_.at(id).position);
  // Keyframe 0 first (fixed, the world), then every observer, free.
  std::unordered_map<KeyFrameId, int> pose_index;
  if (keyframes_.count(0)) AddBundlePoseLocked(0, true, &bundle, &pose_index);
  // The origins of maps not merged yet stay where they are too (AddBundlePoseLocked).
  AddBundleObservationsLocked(/*fix_new_poses=*/false, &bundle, &pose_index);
  // Without observations keyframe 0 would hold nothing in place: leave it
  // out and fix the oldest observer instead.
  const bool zero_observed =
      std::any_of(bundle.problem.observations.begin(), bundle.problem.observations.end(),
                  [&](const BundleProblem::Observation& o) { return bundle.pose_ids[o.pose] == 0; });
  if (!bundle.pose_ids.empty() && bundle.pose_ids.front() == 0 && !zero_observed) {
    bundle.pose_ids.erase(bundle.pose_ids.begin());
    bundle.problem.poses.erase(bundle.problem.poses.begin());
    for (auto& o : bundle.problem.observations) --o.pose;
  }
  if (!bundle.pose_ids.empty() && bundle.pose_ids.front() != 0) {
    const auto oldest = std::min_element(bundle.pose_ids.begin(), bundle.pose_ids.end());
    bundle.problem.poses[oldest - bundle.pose_ids.begin()].fixed = true;
  }
  return bundle;
}

void Map::SetAnchor(KeyFrameId keyframe) {
  std::lock_guard lock(mutex_);
  if (keyframe != 0) anchors_.insert(keyframe);
}

void Map::ClearAnchor(KeyFrameId keyframe) {
  std::lock_guard lock(mutex_);
  anchors_.erase(keyframe);
}

bool Map::IsAnchor(KeyFrameId keyframe) const {
  std::lock_guard lock(mutex_);
  return IsAnchorLocked(keyframe);
}

KeyFrameId Map::MapOrigin(KeyFrameId keyframe) const {
  std::lock_guard lock(mutex_);
  KeyFrameId origin = 0;
  for (KeyFrameId anchor : anchors_) {
    if (anchor <= keyframe && anchor > origin) origin = anchor;
  }
  return origin;
}

void Map::ApplyGlobalBundle(const LocalBundle& bundle, const std::vector<bool>& outlier) {
  DLSLAM_CHECK_EQ(outlier.size(), bundle.problem.observations.size());
  DLSLAM_CHECK_EQ(bundle.pose_ids.size(), bundle.problem.poses.size());
  DLSLAM_CHECK_EQ(bundle.point_ids.size(), bundle.problem.points.size());
  std::lock_guard lock(mutex_);
  std::unordered_map<KeyFrameId, SE3d> old_cam_from_world;
  for (const auto& [id, kf] : keyframes_) old_cam_from_world.emplace(id, kf.cam_from_world);
  ApplyBundleLocked(bundle, outlier);
  std::unordered_set<KeyFrameId> moved;
  const std::unordered_set<KeyFrameId> in_bundle(bundle.pose_ids.begin(), bundle.pose_ids.end());
  for (const auto& [id, kf] : keyframes_) {
    if (kf.cam_from_world.matrix() != old_cam_from_world.at(id).matrix()) moved.insert(id);
  }
  std::unordered_set<KeyFrameId> followers;
  for (const auto& [id, kf] : keyframes_) {
    if (!in_bundle.count(id)) followers.insert(id);
  }
  const std::unordered_set<MapPointId> placed(bundle.point_ids.begin(), bundle.point_ids.end());
  ++generation_;
  PropagateCorrectionLocked(old_cam_from_world, std::move(moved), followers, placed);
}

int Map::PropagateCorrectionLocked(const std::unordered_map<KeyFrameId, SE3d>& old_cam_from_world,
                                   std::unordered_set<KeyFrameId> moved,
                                   const std::unordered_set<KeyFrameId>& followers,
                                   const std::unordered_set<MapPointId>& placed_points) {
  // Followers in id order; each walks up to the first ancestor that is
  // settled (moved, not a follower, or already visited), then the chain
  // takes the motion top-down. A visited set stops parent cycles.
  std::vector<KeyFrameId> order(followers.begin(), followers.end());
  std::sort(order.begin(), order.end());
  std::unordered_set<KeyFrameId> visited;
  for (KeyFrameId start : order) {
    std::vector<KeyFrameId> chain;
    KeyFrameId id = start;
    while (id != kNoId && followers.count(id) && !moved.count(id) && visited.insert(id).second) {
      chain.push_back(id);
      const auto it = keyframes_.find(id);
      id = it == keyframes_.end() ? kNoId : it->second.parent;
    }
    if (id == kNoId || !moved.count(id) || !keyframes_.count(id)) continue;  // the chain's root stayed
    for (auto child = chain.rbegin(); child != chain.rend(); ++child) {
      KeyFrame& kf = keyframes_.at(*child);
      const SE3d cam_from_parent = old_cam_from_world.at(*child) * old_cam_from_world.at(kf.parent).Inverse();
      kf.cam_from_world = cam_from_parent * keyframes_.at(kf.parent).cam_from_world;
      moved.insert(*child);
    }
  }
  for (auto& [pid, p] : points_) {
    bool changed = placed_points.count(pid) > 0;
    if (!changed) {
      KeyFrameId anchor = kNoId;
      if (keyframes_.count(p.reference_keyframe)) {
        if (moved.count(p.reference_keyframe)) anchor = p.reference_keyframe;
      } else {
        for (const auto& [kf_id, idx] : p.observations) {
          if (moved.count(kf_id)) {
            anchor = kf_id;
            break;
          }
        }
      }
      if (anchor != kNoId) {
        p.position = keyframes_.at(anchor).cam_from_world.Inverse() * (old_cam_from_world.at(anchor) * p.position);
        changed = true;
      }
    }
    for (auto obs = p.observations.begin(); !changed && obs != p.observations.end(); ++obs) {
      changed = moved.count(obs->first) > 0;
    }
    if (changed) RefreshPoint(p);  // normal and distance range follow the cameras
  }
  return static_cast<int>(moved.size());
}

bool Map::ReplacePoint(MapPointId from, MapPointId into) {
  std::lock_guard lock(mutex_);
  if (from == into || !points_.count(from) || !points_.count(into)) return false;
  ReplacePointLocked(from, into);
  return true;
}

std::uint64_t Map::Generation() const {
  std::lock_guard lock(mutex_);
  return generation_;
}

}  // namespace dlslam

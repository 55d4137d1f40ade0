#include "dlslam/map/map.h"

#include <algorithm>
#include <bit>

#include "dlslam/util/check.h"

namespace dlslam {


KeyFrameId Map::AddKeyFrame(std::shared_ptr<const Frame> frame, const SE3d& cam_from_world) {
  DLSLAM_CHECK(frame != nullptr);
  std::lock_guard lock(mutex_);
  KeyFrame kf;
  kf.id = next_keyframe_id_++;
  kf.cam_from_world = cam_from_world;
  kf.points.assign(frame->size(), kNoId);
  kf.frame = std::move(frame);
  const KeyFrameId id = kf.id;
  keyframes_.emplace(id, std::move(kf));
  return id;
}

MapPointId Map::AddMapPoint(const Eigen::Vector3d& position, KeyFrameId keyframe, int keypoint) {
  std::lock_guard lock(mutex_);
  KeyFrame& kf = keyframes_.at(keyframe);
  DLSLAM_CHECK(keypoint >= 0 && keypoint < static_cast<int>(kf.points.size()));
  DLSLAM_CHECK_EQ(kf.points[keypoint], kNoId, "keypoint already has a point");
  MapPoint p;
  p.id = next_point_id_++;
  p.position = position;
  p.observations[keyframe] = keypoint;
  p.reference_keyframe = keyframe;
  p.first_keyframe = keyframe;
  kf.points[keypoint] = p.id;
  RefreshPoint(p);
  const MapPointId id = p.id;
  points_.emplace(id, std::move(p));
  return id;
}

bool Map::AddObservation(MapPointId point, KeyFrameId keyframe, int keypoint) {
  std::lock_guard lock(mutex_);
  const auto kf_it = keyframes_.find(keyframe);
  const auto p_it = points_.find(point);
  // Local mapping may have culled either since the caller looked.
  if (kf_it == keyframes_.end() || p_it == points_.end()) return false;
  KeyFrame& kf = kf_it->second;
  MapPoint& p = p_it->second;
  if (kf.points.at(keypoint) != kNoId || p.observations.count(keyframe)) return false;
  kf.points[keypoint] = point;
  p.observations[keyframe] = keypoint;
  RefreshPoint(p);
  return true;
}

void Map::RefreshPoint(MapPoint& p) const {
  // Descriptor: the observation with the least median distance to the others.
  std::vector<Descriptor> descriptors;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const auto& [kf_id, idx] : p.observations) {
    const KeyFrame& kf = keyframes_.at(kf_id);
    descriptors.push_back(DescriptorOf(*kf.frame, idx));
    const Eigen::Vector3d centre = kf.cam_from_world.Inverse().translation();
    normal += (p.position - centre).normalized();
  }
  if (descriptors.size() > 2) {
    int best = 0;
    int best_median = 1 << 30;
    for (std::size_t i = 0; i < descriptors.size(); ++i) {
      std::vector<int> d;
      for (std::size_t j = 0; j < descriptors.size(); ++j) d.push_back(HammingDistance(descriptors[i].data(), descriptors[j].data()));
      std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
      if (d[d.size() / 2] < best_median) {
        best_median = d[d.size() / 2];
        best = static_cast<int>(i);
      }
    }
    p.descriptor = descriptors[best];
  } else {
    p.descriptor = descriptors.front();
  }
  p.normal = normal.normalized();
  // Distance range from the reference observation's pyramid level.
  const KeyFrame& ref = keyframes_.at(p.reference_keyframe);
  const int idx = p.observations.at(p.reference_keyframe);
  const ScalePyramid& pyr = ref.frame->pyramid();
  const double distance = (p.position - ref.cam_from_world.Inverse().translation()).norm();
  const int octave = ref.frame->keypoint(idx).octave;
  p.max_distance = distance * pyr.Scale(octave);
  p.min_distance = p.max_distance / pyr.Scale(pyr.levels - 1);
}

void Map::UpdateConnections(KeyFrameId keyframe, int min_shared) {
  std::lock_guard lock(mutex_);
  const auto kf_it = keyframes_.find(keyframe);
  if (kf_it == keyframes_.end()) return;  // culled since the caller looked
  KeyFrame& kf = kf_it->second;
  std::map<KeyFrameId, int> counts;
  for (MapPointId pid : kf.points) {
    if (pid == kNoId) continue;
    for (const auto& [other, idx] : points_.at(pid).observations) {
      if (other != keyframe) ++counts[other];
    }
  }
  // Drop old edges, then add the new ones on both sides.
  for (const auto& [other, w] : kf.covisibility) keyframes_.at(other).covisibility.erase(keyframe);
  kf.covisibility.clear();
  KeyFrameId best = kNoId;
  int best_count = 0;
  for (const auto& [other, count] : counts) {
    if (count > best_count) {
      best_count = count;
      best = other;
    }
    if (count >= min_shared) {
      kf.covisibility[other] = count;
      keyframes_.at(other).covisibility[keyframe] = count;
    }
  }
  if (best != kNoId) {
    kf.covisibility[best] = best_count;
    keyframes_.at(best).covisibility[keyframe] = best_count;
    // Spanning tree: a keyframe's parent is its best older neighbour, set once.
    if (kf.parent == kNoId && best < keyframe) kf.parent = best;
  }
}

namespace {

// A set of map point ids sized once for at most `capacity` of them: open
// addressing with linear probing in a power-of-two table at most half full.
// The local map inserts every point of ~40 keyframes each frame; with
// std::unordered_set that was most of the call (1.03 ms in BM_GetLocalMap).
class IdSet {
 public:
  explicit IdSet(std::size_t capacity) : slots_(std::bit_ceil(2 * capacity + 2), kNoId), mask_(slots_.size() - 1) {}
  // False when `id` (never kNoId) was in already.
  bool Insert(MapPointId id) {
    // Fibonacci hashing spreads consecutive ids (they are handed out in order).
    for (std::size_t i = ((id * 0x9E3779B97F4A7C15ull) >> 32) & mask_;; i = (i + 1) & mask_) {
      if (slots_[i] == id) return false;
      if (slots_[i] == kNoId) {
        slots_[i] = id;
        return true;
      }
    }
  }

 private:
  std::vector<MapPointId> slots_;
  std::size_t mask_;
};

}  // namespace

LocalMapSnapshot Map::GetLocalMap(const std::vector<MapPointId>& matched_points, std::size_t max_keyframes) const {
  std::lock_guard lock(mutex_);
  LocalMapSnapshot snap;
  std::map<KeyFrameId, int> votes;
  for (MapPointId pid : matched_points) {
    const auto it = points_.find(pid);
    if (it == points_.end()) continue;
    for (const auto& [kf_id, idx] : it->second.observations) ++votes[kf_id];
  }
  if (votes.empty()) return snap;
  std::vector<std::pair<int, KeyFrameId>> ranked;
  for (const auto& [kf_id, n] : votes) ranked.emplace_back(n, kf_id);
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second > b.second;
  });
  snap.reference = ranked.front().second;
  std::unordered_set<KeyFrameId> chosen;
  const auto take = [&](KeyFrameId id) {
    if (snap.keyframes.size() < max_keyframes && chosen.insert(id).second) snap.keyframes.push_back(id);
  };
  for (const auto& [n, id] : ranked) take(id);
  // Neighbours of the voted keyframes: best covisible ones and the parent.
  const std::size_t voted = snap.keyframes.size();
  for (std::size_t i = 0; i < voted; ++i) {
    const KeyFrame& kf = keyframes_.at(snap.keyframes[i]);
    std::vector<std::pair<int, KeyFrameId>> neighbours;
    for (const auto& [other, w] : kf.covisibility) neighbours.emplace_back(w, other);
    std::sort(neighbours.rbegin(), neighbours.rend());
    for (std::size_t k = 0; k < std::min<std::size_t>(10, neighbours.size()); ++k) take(neighbours[k].second);
    if (kf.parent != kNoId) take(kf.parent);
  }
  std::size_t slots = 0;
  for (KeyFrameId id : snap.keyframes) slots += keyframes_.at(id).points.size();
  IdSet seen(slots);
  snap.points.reserve(slots);
  for (KeyFrameId id : snap.keyframes) {
    for (MapPointId pid : keyframes_.at(id).points) {
      if (pid == kNoId || !seen.Insert(pid)) continue;
      const MapPoint& p = points_.at(pid);
      snap.points.push_back({p.id, p.position, p.descriptor, p.normal, p.min_distance, p.max_distance});
    }
  }
  return snap;
}

std::vector<MapPointView> Map::GetPoints(const std::vector<MapPointId>& ids) const {
  std::lock_guard lock(mutex_);
  std::vector<MapPointView> out;
  out.reserve(ids.size());
  for (MapPointId id : ids) {
    const auto it = points_.find(id);
    if (it == points_.end()) continue;
    const MapPoint& p = it->second;
    out.push_back({p.id, p.position, p.descriptor, p.normal, p.min_distance, p.max_distance});
  }
  return out;
}

void Map::RecordVisibility(const std::vector<MapPointId>& visible, const std::vector<MapPointId>& found) {
  std::lock_guard lock(mutex_);
  for (MapPointId id : visible) {
    if (auto it = points_.find(id); it != points_.end()) ++it->second.times_visible;
  }
  for (MapPointId id : found) {
    if (auto it = points_.find(id); it != points_.end()) ++it->second.times_found;
  }
}

int Map::TrackedPoints(KeyFrameId keyframe, int min_observations) const {
  std::lock_guard lock(mutex_);
  const auto it = keyframes_.find(keyframe);
  if (it == keyframes_.end()) return 0;
  int n = 0;
  for (MapPointId pid : it->second.points) {
    if (pid == kNoId) continue;
    int observations = 0;
    for (const auto& [kf_id, idx] : points_.at(pid).observations) {
      observations += keyframes_.at(kf_id).frame->keypoint(idx).right_u >= 0 ? 2 : 1;
    }
    n += observations >= min_observations;
  }
  return n;
}

std::vector<KeyFramePose> Map::KeyFramePoses() const {
  std::lock_guard lock(mutex_);
  std::vector<KeyFramePose> out;
  for (const auto& [id, kf] : keyframes_) out.push_back({id, kf.frame->timestamp(), kf.cam_from_world});
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

std::optional<KeyFrameSnapshot> Map::GetKeyFrame(KeyFrameId keyframe) const {
  std::lock_guard lock(mutex_);
  const auto it = keyframes_.find(keyframe);
  if (it == keyframes_.end()) return std::nullopt;
  const KeyFrame& kf = it->second;
  return KeyFrameSnapshot{kf.id, kf.frame, kf.cam_from_world, kf.points};
}

std::vector<KeyFrameSnapshot> Map::GetCovisibleKeyFrames(KeyFrameId keyframe, std::size_t max_keyframes) const {
  std::lock_guard lock(mutex_);
  std::vector<KeyFrameSnapshot> out;
  if (keyframes_.empty() || max_keyframes == 0) return out;
  auto it = keyframes_.find(keyframe);
  if (it == keyframes_.end()) {
    it = std::max_element(keyframes_.begin(), keyframes_.end(),
                          [](const auto& a, const auto& b) { return a.first < b.first; });
  }
  const auto copy = [&](const KeyFrame& kf) { out.push_back({kf.id, kf.frame, kf.cam_from_world, kf.points}); };
  copy(it->second);
  // Most shared points first; among equals the newer keyframe.
  std::vector<std::pair<int, KeyFrameId>> neighbours;
  for (const auto& [other, shared] : it->second.covisibility) neighbours.emplace_back(shared, other);
  std::sort(neighbours.rbegin(), neighbours.rend());
  for (const auto& [shared, other] : neighbours) {
    if (out.size() >= max_keyframes) break;
    if (const auto n = keyframes_.find(other); n != keyframes_.end()) copy(n->second);
  }
  return out;
}

int Map::ErasePoints(const std::vector<MapPointId>& ids) {
  std::lock_guard lock(mutex_);
  int erased = 0;
  for (MapPointId id : ids) {
    if (!points_.count(id)) continue;
    ErasePointLocked(id);
    ++erased;
  }
  return erased;
}

std::size_t Map::NumKeyFrames() const {
  std::lock_guard lock(mutex_);
  return keyframes_.size();
}

std::size_t Map::NumMapPoints() const {
  std::lock_guard lock(mutex_);
  return points_.size();
}

}  // namespace dlslam

#include "dlslam/mapping/fusion.h"

#include <algorithm>
#include <unordered_set>

#include "dlslam/util/check.h"

namespace dlslam {

void FusionOptions::Check() const {
  DLSLAM_CHECK_GE(neighbours, 0);
  DLSLAM_CHECK_GE(second_neighbours, 0);
  match.Check();
}

namespace {

std::vector<MapPointId> ValidIds(const std::vector<MapPointId>& points) {
  std::vector<MapPointId> ids;
  for (MapPointId id : points) {
    if (id != kNoId) ids.push_back(id);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

}  // namespace

FusionStats FuseWithNeighbours(Map* map, KeyFrameId keyframe, const FusionOptions& options) {
  options.Check();
  FusionStats stats;
  std::vector<KeyFrameId> targets;
  std::unordered_set<KeyFrameId> chosen{keyframe};
  for (KeyFrameId first : map->BestCovisible(keyframe, options.neighbours, keyframe)) {
    if (chosen.insert(first).second) targets.push_back(first);
    for (KeyFrameId second : map->BestCovisible(first, options.second_neighbours, keyframe)) {
      if (chosen.insert(second).second) targets.push_back(second);
    }
  }
  std::optional<KeyFrameSnapshot> current = map->GetKeyFrame(keyframe);
  if (!current || targets.empty()) return stats;

  // The keyframe's points into each neighbour.
  const std::vector<MapPointView> own = map->GetPoints(ValidIds(current->points));
  std::vector<MapPointId> theirs;
  for (KeyFrameId target : targets) {
    const std::optional<KeyFrameSnapshot> kf = map->GetKeyFrame(target);
    if (!kf) continue;
    ++stats.targets;
    for (const FuseCandidate& c : SearchForFusion(*kf->frame, kf->cam_from_world, kf->points, own, options.match)) {
      stats.fused += map->FusePoint(c.point, target, c.keypoint);
    }
    // Read again: the fusion above changed its points.
    if (const auto after = map->GetKeyFrame(target)) {
      for (MapPointId id : after->points) {
        if (id != kNoId) theirs.push_back(id);
      }
    }
  }

  // The neighbours' points into the keyframe.
  current = map->GetKeyFrame(keyframe);
  if (!current) return stats;
  const std::vector<MapPointView> candidates = map->GetPoints(ValidIds(theirs));
  for (const FuseCandidate& c :
       SearchForFusion(*current->frame, current->cam_from_world, current->points, candidates, options.match)) {
    stats.fused += map->FusePoint(c.point, keyframe, c.keypoint);
  }
  map->UpdateConnections(keyframe);
  return stats;
}

}  // namespace dlslam

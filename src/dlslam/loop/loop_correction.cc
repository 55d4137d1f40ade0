#include "dlslam/loop/loop_correction.h"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "dlslam/util/check.h"

namespace dlslam {

namespace {

constexpr std::size_t kAllNeighbours = 100000;
constexpr double kRadToDeg = 57.29577951308232;

bool SamePose(const SE3d& a, const SE3d& b) {
  return (a.translation() - b.translation()).norm() < 1e-12 &&
         (a.so3().matrix() - b.so3().matrix()).norm() < 1e-12;
}

// Fuses the loop side's points into keyframe `id`: a keypoint without a point
// observes the loop point; one with a different point has it replaced.
int FuseInto(Map* map, KeyFrameId id, const std::vector<MapPointView>& loop_points, const FuseMatchOptions& options) {
  const std::optional<KeyFrameSnapshot> kf = map->GetKeyFrame(id);
  if (!kf) return 0;
  int fused = 0;
  for (const FuseCandidate& c : SearchForFusion(*kf->frame, kf->cam_from_world, kf->points, loop_points, options)) {
    const MapPointId own = kf->points[c.keypoint];
    if (own == kNoId) {
      fused += map->AddObservation(c.point, id, c.keypoint);
    } else if (own != c.point) {
      fused += map->ReplacePoint(own, c.point);
    }
  }
  return fused;
}

}  // namespace

void LoopCorrectionOptions::Check() const {
  DLSLAM_CHECK_GE(min_covisibility, 1);
  DLSLAM_CHECK_GE(loop_group_keyframes, 1);
  fuse.Check();
  pose_graph.Check();
}

LoopCorrection CloseLoop(Map* map, const LoopMatch& loop, const LoopCorrectionOptions& options) {
  DLSLAM_CHECK(map != nullptr);
  options.Check();
  LoopCorrection out;
  std::unordered_map<KeyFrameId, SE3d> before;
  for (const KeyFramePose& k : map->KeyFramePoses()) before.emplace(k.id, k.cam_from_world);
  const auto current_it = before.find(loop.current);
  if (current_it == before.end() || !before.count(loop.loop)) return out;  // culled meanwhile
  const SE3d current_before = current_it->second;
  const SE3d drift = loop.corrected_cam_from_world.Inverse() * current_before;
  out.correction_m = drift.translation().norm();
  out.correction_deg = drift.so3().Log().norm() * kRadToDeg;

  // 1. The keyframe's neighbourhood moves rigidly with it.
  std::vector<KeyFrameId> group = map->BestCovisible(loop.current, kAllNeighbours);
  group.push_back(loop.current);
  std::unordered_map<KeyFrameId, std::set<KeyFrameId>> linked_before;
  std::unordered_map<KeyFrameId, SE3d> corrected;
  for (KeyFrameId id : group) {
    const auto it = before.find(id);
    if (it == before.end()) continue;
    corrected.emplace(id, it->second * current_before.Inverse() * loop.corrected_cam_from_world);
    const std::vector<KeyFrameId> linked = map->BestCovisible(id, kAllNeighbours);
    linked_before.emplace(id, std::set<KeyFrameId>(linked.begin(), linked.end()));
  }
  map->ApplyCorrectedPoses(corrected);

  // 2. Loop fusion: the verified matches first, then the loop side's points
  // projected into the whole neighbourhood.
  const std::optional<KeyFrameSnapshot> current = map->GetKeyFrame(loop.current);
  if (!current) return out;
  for (std::size_t i = 0; i < loop.matches.size() && i < current->points.size(); ++i) {
    const MapPointId loop_point = loop.matches[i];
    if (loop_point == kNoId) continue;
    const MapPointId own = current->points[i];
    if (own == kNoId) {
      out.points_fused += map->AddObservation(loop_point, loop.current, static_cast<int>(i));
    } else if (own != loop_point) {
      out.points_fused += map->ReplacePoint(own, loop_point);
    }
  }
  std::vector<MapPointId> loop_ids;
  for (const KeyFrameSnapshot& k :
       map->GetCovisibleKeyFrames(loop.loop, static_cast<std::size_t>(options.loop_group_keyframes))) {
    for (MapPointId id : k.points) {
      if (id != kNoId) loop_ids.push_back(id);
    }
  }
  std::sort(loop_ids.begin(), loop_ids.end());
  loop_ids.erase(std::unique(loop_ids.begin(), loop_ids.end()), loop_ids.end());
  const std::vector<MapPointView> loop_points = map->GetPoints(loop_ids);
  for (KeyFrameId id : group) out.points_fused += FuseInto(map, id, loop_points, options.fuse);
  for (KeyFrameId id : group) {
    if (map->GetKeyFrame(id)) map->UpdateConnections(id);
  }
  map->AddLoopEdge(loop.current, loop.loop);

  // 3. Pose graph. Edges that cross from the moved neighbourhood to the rest
  // of the map keep their measurement from before the move (that is the
  // error to spread); only the new links made by the fusion, and the loop
  // edges, are measured on the corrected poses.
  EssentialGraph graph = map->GetEssentialGraph(options.min_covisibility);
  if (graph.ids.empty()) return out;
  const auto moved = [&](KeyFrameId id) { return corrected.count(id) > 0; };
  PoseGraph pose_graph;
  pose_graph.cam_from_world = graph.cam_from_world;
  // The oldest keyframe defines the world; each map not merged yet is held
  // by its own first keyframe.
  pose_graph.fixed.resize(graph.ids.size());
  for (std::size_t n = 0; n < graph.ids.size(); ++n) pose_graph.fixed[n] = n == 0 || map->IsAnchor(graph.ids[n]);
  for (const EssentialGraph::Edge& e : graph.edges) {
    PoseGraphEdge edge{e.from, e.to, e.to_from_from, 1.0};
    const KeyFrameId a = graph.ids[e.from];
    const KeyFrameId b = graph.ids[e.to];
    if (e.kind != EssentialGraph::Edge::Kind::kLoop && moved(a) != moved(b)) {
      const KeyFrameId inside = moved(a) ? a : b;
      const KeyFrameId outside = moved(a) ? b : a;
      const bool new_link = !linked_before.at(inside).count(outside);
      if (!new_link && before.count(a) && before.count(b)) {
        edge.to_from_from = before.at(b) * before.at(a).Inverse();
      }
    }
    pose_graph.edges.push_back(edge);
  }
  const PoseGraphSummary summary = OptimizePoseGraph(&pose_graph, options.pose_graph);
  out.graph_nodes = static_cast<int>(graph.ids.size());
  out.graph_edges = static_cast<int>(graph.edges.size());
  out.pose_graph_initial_cost = summary.initial_cost;
  out.pose_graph_final_cost = summary.final_cost;
  std::unordered_map<KeyFrameId, SE3d> optimised;
  for (std::size_t n = 0; n < graph.ids.size(); ++n) {
    optimised.emplace(graph.ids[n], pose_graph.cam_from_world[n]);
    const auto it = before.find(graph.ids[n]);
    out.keyframes_moved += it == before.end() || !SamePose(it->second, pose_graph.cam_from_world[n]);
  }
  map->ApplyCorrectedPoses(optimised);
  return out;
}

}  // namespace dlslam

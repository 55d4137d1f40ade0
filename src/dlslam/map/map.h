#pragma once
// The map: keyframes, map points and the covisibility graph. The one
// structure that several threads share: its lock lives inside, every call is
// short, and readers get copies (views), so no caller ever holds the lock
// across heavy work.

#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "dlslam/map/map_types.h"
#include "dlslam/optimize/bundle_adjuster.h"

namespace dlslam {

// A copy of the part of the map that tracking searches in.
struct LocalMapSnapshot {
  std::vector<KeyFrameId> keyframes;  // the local keyframes, best first
  KeyFrameId reference = kNoId;       // the one sharing most points with the frame
  std::vector<MapPointView> points;   // every point the local keyframes observe
};

// A copy of one keyframe (the frame itself is shared and immutable).
struct KeyFrameSnapshot {
  KeyFrameId id = kNoId;
  std::shared_ptr<const Frame> frame;
  SE3d cam_from_world;
  std::vector<MapPointId> points;  // per keypoint; kNoId if none
};

// A local bundle adjustment problem cut out of the map, with the ids that
// its indices stand for.
struct LocalBundle {
  BundleProblem problem;
  std::vector<KeyFrameId> pose_ids;   // per problem.poses
  std::vector<MapPointId> point_ids;  // per problem.points
  std::vector<int> keypoints;         // per problem.observations: keypoint index
};

// ORB-SLAM's essential graph as the input of a pose graph: spanning-tree
// edges, strong covisibility edges and loop edges, measured at the current
// poses. Node i stands for ids[i].
struct EssentialGraph {
  std::vector<KeyFrameId> ids;       // sorted
  std::vector<SE3d> cam_from_world;  // per node, its current pose
  struct Edge {
    enum class Kind { kTree, kCovisibility, kLoop };
    int from = 0;  // node index, from < to
    int to = 0;
    SE3d to_from_from;  // cam_from_world[to] * cam_from_world[from].Inverse()
    Kind kind = Kind::kCovisibility;
  };
  // Each undirected pair at most once, sorted by (from, to); a pair that is
  // several kinds at once is kLoop before kTree before kCovisibility.
  std::vector<Edge> edges;
};

struct KeyFramePose {
  KeyFrameId id = kNoId;
  double timestamp = 0.0;
  SE3d cam_from_world;
};

class Map {
 public:
  Map() = default;
  Map(const Map&) = delete;
  Map& operator=(const Map&) = delete;

  // Adds a keyframe for `frame` at `cam_from_world`, with no points yet.
  KeyFrameId AddKeyFrame(std::shared_ptr<const Frame> frame, const SE3d& cam_from_world);
  // A new point at `position` (world) first seen by keypoint `keypoint` of `keyframe`.
  MapPointId AddMapPoint(const Eigen::Vector3d& position, KeyFrameId keyframe, int keypoint);
  // Point `point` is also seen by keypoint `keypoint` of `keyframe`. Refreshes
  // the point's descriptor, normal and distance range. False if the keypoint
  // already has a point, or the point or keyframe no longer exists.
  bool AddObservation(MapPointId point, KeyFrameId keyframe, int keypoint);
  // Recomputes the covisibility edges of `keyframe` (min_shared points make an
  // edge; the best neighbour always does) and its spanning-tree parent.
  // No-op for a keyframe that is gone (culled meanwhile).
  void UpdateConnections(KeyFrameId keyframe, int min_shared = 15);

  // The local map of a frame whose keypoints matched `matched_points`:
  // keyframes observing them, their best covisible neighbours, and all their
  // points (ORB-SLAM's local map), at most max_keyframes keyframes.
  LocalMapSnapshot GetLocalMap(const std::vector<MapPointId>& matched_points, std::size_t max_keyframes = 80) const;
  // Views of the given points (unknown ids are skipped).
  std::vector<MapPointView> GetPoints(const std::vector<MapPointId>& ids) const;
  // Tracking statistics used to cull unreliable points.
  void RecordVisibility(const std::vector<MapPointId>& visible, const std::vector<MapPointId>& found);

  // Number of points of `keyframe` with at least min_observations
  // observations, one with depth counting twice (a virtual stereo pair, as
  // ORB-SLAM counts them); 0 for a culled keyframe.
  int TrackedPoints(KeyFrameId keyframe, int min_observations) const;
  std::vector<KeyFramePose> KeyFramePoses() const;  // sorted by id
  std::optional<KeyFrameSnapshot> GetKeyFrame(KeyFrameId keyframe) const;
  // Copies of `keyframe` and its covisible neighbours that share the most
  // points with it, best first, at most `max_keyframes` in all: the views
  // with most overlap with a frame tracked against `keyframe`. A culled or
  // unknown `keyframe` is replaced by the newest keyframe (empty: no map).
  std::vector<KeyFrameSnapshot> GetCovisibleKeyFrames(KeyFrameId keyframe, std::size_t max_keyframes) const;
  std::size_t NumKeyFrames() const;
  std::size_t NumMapPoints() const;
  // Pose of a keyframe, also of one that was culled (through its parent).
  std::optional<SE3d> ResolveCamFromWorld(KeyFrameId keyframe) const;

  // Removes the given points (ones already gone are skipped), e.g. points
  // that turned out to lie on a moving object. Returns how many were removed.
  int ErasePoints(const std::vector<MapPointId>& ids);

  // --- Maintenance by local mapping (map_maintenance.cc) ---
  // `keyframe` and its covisible neighbours, free; every other keyframe that
  // sees their points, fixed; keyframe 0 always fixed (it defines the world).
  LocalBundle BuildLocalBundle(KeyFrameId keyframe) const;
  // Writes back poses and positions of entities that still exist, and drops
  // the observations flagged as outliers.
  void ApplyLocalBundle(const LocalBundle& bundle, const std::vector<bool>& outlier);
  // Removes points created in the last keyframes that tracking rarely finds
  // (found / visible < min_found_ratio) or that too few keyframes observe
  // once two keyframes have passed. Returns how many were removed.
  int CullRecentPoints(KeyFrameId current, int min_observations = 3, double min_found_ratio = 0.25);
  // Removes covisible neighbours of `current` (never an anchor, one with a
  // loop edge, `current` or a newer one) whose close points are nearly all (redundancy) seen by at
  // least min_views other keyframes at the same or a finer scale. Returns them.
  std::vector<KeyFrameId> CullRedundantKeyFrames(KeyFrameId current, double close_depth, double redundancy = 0.9,
                                                 int min_views = 3);

  // --- New points and fusion by local mapping (map_fusion.cc) ---
  // The n covisible neighbours of `keyframe` sharing most points, best first
  // (ties: newer first), leaving out keyframes with an id above max_id.
  std::vector<KeyFrameId> BestCovisible(KeyFrameId keyframe, std::size_t n, KeyFrameId max_id = kNoId) const;
  // A point triangulated from keypoint1 of keyframe1 and keypoint2 of
  // keyframe2, observed by both (keyframe1 is its reference). No-op returning
  // kNoId when either keyframe is gone or either keypoint already has a point.
  MapPointId AddTriangulatedPoint(const Eigen::Vector3d& position, KeyFrameId keyframe1, int keypoint1,
                                  KeyFrameId keyframe2, int keypoint2);
  // Point `point` projects onto keypoint `keypoint` of `keyframe`: adds the
  // observation, or, when the keypoint already holds another point, merges
  // the two into the one observed by more keyframes. Returns false when
  // nothing changed (point or keyframe gone, or the keyframe already sees it).
  bool FusePoint(MapPointId point, KeyFrameId keyframe, int keypoint);

  // --- Loop closing (map_loop.cc) ---
  // Joins a and b by a loop edge (both directions). Keyframes with a loop
  // edge are never culled. No-op if either is gone or a == b.
  void AddLoopEdge(KeyFrameId a, KeyFrameId b);
  // The essential graph: parent edges, covisibility edges of at least
  // min_covisibility shared points, loop edges.
  EssentialGraph GetEssentialGraph(int min_covisibility = 100) const;
  // Sets the poses of the keyframes in `corrected` (cam_from_world; ids that
  // are gone are skipped). Keyframes not in `corrected` that are newer than
  // every keyframe in it (tracking kept adding them meanwhile) follow their
  // spanning-tree parent rigidly (recursively). Every map point moves
  // rigidly with its reference keyframe (p' = world_from_cam_new *
  // cam_from_world_old * p) when that keyframe moved; a point whose
  // reference keyframe is gone uses the first observing keyframe that moved.
  // Culled keyframes are stored relative to their parent and so follow it.
  // A keyframe moved when its pose changed. Bumps Generation() unless
  // `corrected` names no existing keyframe. Returns the number of keyframes
  // moved.
  int ApplyCorrectedPoses(const std::unordered_map<KeyFrameId, SE3d>& corrected);
  // The whole map as a bundle: every keyframe that sees a point of it, free
  // except the anchors (keyframe 0 fixed; if it sees none, the oldest keyframe in the
  // bundle), and every point with at least 2 observations. Observations as
  // in BuildLocalBundle.
  LocalBundle BuildGlobalBundle() const;
  // Writes back the bundle's free poses and its points, drops the outlier
  // observations (as ApplyLocalBundle); keyframes and points not in the
  // bundle (newer ones, points with one observation) move with their parent
  // / reference keyframe as in ApplyCorrectedPoses. Bumps Generation().
  void ApplyGlobalBundle(const LocalBundle& bundle, const std::vector<bool>& outlier);
  // Public ReplacePointLocked: `from`'s observations move to `into` and
  // `from` is erased. False when either is gone or from == into.
  bool ReplacePoint(MapPointId from, MapPointId into);
  // Every point's position (for views): one short pass under the lock.
  std::vector<Eigen::Vector3d> PointPositions() const;

  // --- Persistence (map_contents.cc) ---
  // A deep copy of everything, sorted by id (the frames stay shared).
  MapContents Export() const;
  // Replaces an empty map by `contents`, after checking that it is one map:
  // every id it refers to exists, keypoint indices are in range, point and
  // keyframe views agree, numbers are finite. Throws dlslam::Error naming
  // the first defect (the map stays empty).
  void Import(MapContents contents);

  // --- Several maps in one (map_loop.cc) ---
  // A keyframe that starts a map of its own (the tracker was lost and could
  // not relocalize): like keyframe 0 it is fixed in every bundle, never
  // culled and fixed in pose graphs, until the map it starts is merged into
  // an older one (ClearAnchor). Keyframe 0 is always an anchor.
  void SetAnchor(KeyFrameId keyframe);
  void ClearAnchor(KeyFrameId keyframe);
  bool IsAnchor(KeyFrameId keyframe) const;
  // The anchor that starts the map `keyframe` belongs to: the newest anchor
  // not newer than it (maps start one after another; 0 for the first map).
  KeyFrameId MapOrigin(KeyFrameId keyframe) const;

  // Counts the corrections (ApplyCorrectedPoses, ApplyGlobalBundle) so that
  // tracking notices that the map moved under it.
  std::uint64_t Generation() const;

 private:
  void RefreshPoint(MapPoint& point) const;  // descriptor, normal, distances
  // These expect the lock to be held.
  void EraseObservationLocked(MapPointId point, KeyFrameId keyframe);
  void ErasePointLocked(MapPointId point);
  void EraseKeyFrameLocked(KeyFrameId keyframe);
  // Moves the observations of `from` to `into` (dropping those of keyframes
  // that already see `into`) and erases `from`.
  void ReplacePointLocked(MapPointId from, MapPointId into);
  // Bundle building shared by the local and the global bundle: adds a pose
  // (fixed if asked or an anchor) unless present; adds the observations of
  // every point in bundle->point_ids, adding their observers as poses
  // (fixed if fix_new_poses).
  void AddBundlePoseLocked(KeyFrameId keyframe, bool fixed, LocalBundle* bundle,
                           std::unordered_map<KeyFrameId, int>* pose_index) const;
  void AddBundleObservationsLocked(bool fix_new_poses, LocalBundle* bundle,
                                   std::unordered_map<KeyFrameId, int>* pose_index) const;
  // ApplyLocalBundle's work: drops outliers, writes free poses and points.
  void ApplyBundleLocked(const LocalBundle& bundle, const std::vector<bool>& outlier);
  // Completes a correction whose `moved` keyframes already hold their new
  // poses (`old_cam_from_world`: every keyframe's pose before it): each of
  // `followers` whose parent moved takes its parent's motion (recursively),
  // points not in `placed_points` move with their reference keyframe, and
  // points that moved or whose observers did are refreshed. Returns the
  // number of keyframes moved, followers included.
  int PropagateCorrectionLocked(const std::unordered_map<KeyFrameId, SE3d>& old_cam_from_world,
                                std::unordered_set<KeyFrameId> moved,
                                const std::unordered_set<KeyFrameId>& followers,
                                const std::unordered_set<MapPointId>& placed_points);

  // Culled keyframes: parent and the transform from it, so that frames
  // tracked against them keep a pose.
  struct Culled {
    KeyFrameId parent = kNoId;
    SE3d cam_from_parent;
  };
  std::unordered_map<KeyFrameId, Culled> culled_;
  bool IsAnchorLocked(KeyFrameId keyframe) const { return keyframe == 0 || anchors_.count(keyframe) > 0; }
  std::unordered_set<KeyFrameId> anchors_;  // besides keyframe 0

  mutable std::mutex mutex_;
  std::unordered_map<KeyFrameId, KeyFrame> keyframes_;
  std::unordered_map<MapPointId, MapPoint> points_;
  KeyFrameId next_keyframe_id_ = 0;
  MapPointId next_point_id_ = 0;
  std::uint64_t generation_ = 0;
};

}  // namespace dlslam

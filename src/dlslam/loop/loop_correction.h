#pragma once
// Closing a verified loop in the map (ORB-SLAM's CorrectLoop for RGB-D,
// written by us; SE(3) throughout, the scale is known):
//   1. the keyframe and its covisible neighbours move rigidly to where the
//      loop says they are, and their points with them;
//   2. the loop side's points are fused into them (duplicates replaced by the
//      older, less drifted points), so the two ends share points again;
//   3. a pose graph over the essential graph (spanning tree, strong
//      covisibility, loop edges) spreads the remaining error along the loop;
//      every point follows its reference keyframe.
// The caller must keep local mapping paused meanwhile (its bundle adjustment
// would write back poses from before the correction); tracking may go on.

#include "dlslam/loop/loop_detector.h"
#include "dlslam/map/map.h"
#include "dlslam/match/fuse_matcher.h"
#include "dlslam/optimize/pose_graph.h"

namespace dlslam {

struct LoopCorrectionOptions {
  // Shared points that make a covisibility edge of the essential graph
  // [count] (ORB-SLAM: 100).
  int min_covisibility = 100;
  // Keyframes of the loop side whose points are fused into the corrected
  // neighbourhood: the loop keyframe and its best neighbours [count].
  int loop_group_keyframes = 10;
  FuseMatchOptions fuse;
  PoseGraphOptions pose_graph;

  void Check() const;  // throws dlslam::Error with the values
};

struct LoopCorrection {
  int keyframes_moved = 0;   // by the pose graph (and the first rigid move)
  int points_fused = 0;      // observations added or points replaced
  int graph_nodes = 0;
  int graph_edges = 0;
  double pose_graph_initial_cost = 0.0;
  double pose_graph_final_cost = 0.0;
  // How far the keyframe was from where the loop put it: the drift closed.
  double correction_m = 0.0;
  double correction_deg = 0.0;
};

LoopCorrection CloseLoop(Map* map, const LoopMatch& loop, const LoopCorrectionOptions& options = {});

}  // namespace dlslam

#pragma once
// SE(3) pose-graph optimisation (the essential graph of a loop closure):
// keyframe poses linked by measured relative transforms. RGB-D fixes the
// scale, so poses live in SE(3), not Sim(3). Solved with Ceres (sparse
// normal Cholesky, autodiff). Knows nothing of the map: plain values in/out.

#include <vector>

#include "dlslam/geometry/se3.h"

namespace dlslam {

// A measured relative pose between two graph poses.
struct PoseGraphEdge {
  int from = 0;  // index into PoseGraph::cam_from_world
  int to = 0;
  // Measured cam_to_from_cam_from (maps points of camera `from` into camera `to`).
  SE3d to_from_from;
  // Scales the whole 6-dof residual (so the cost by weight^2); > 0.
  double weight = 1.0;
};

struct PoseGraph {
  std::vector<SE3d> cam_from_world;
  std::vector<bool> fixed;  // per pose: held constant (at least one must be, it fixes the gauge)
  std::vector<PoseGraphEdge> edges;
};

struct PoseGraphOptions {
  // Levenberg-Marquardt iterations at most.
  int max_iterations = 20;
  // Stop when an iteration lowers the cost by less than this fraction of it (Ceres' function_tolerance).
  double function_tolerance = 1e-8;
  // Stop when the max-norm of the projected gradient falls below this (Ceres' gradient_tolerance).
  double gradient_tolerance = 1e-10;
  // Stop when a step is smaller than this fraction of the parameters' norm (Ceres' parameter_tolerance).
  double parameter_tolerance = 1e-8;
  // Threads Ceres may use for evaluating residuals and Jacobians.
  int threads = 1;

  void Check() const;
};

struct PoseGraphSummary {
  int iterations = 0;         // Levenberg-Marquardt steps tried (accepted or not)
  double initial_cost = 0.0;  // 0.5 * sum over edges of weight^2 * |residual|^2, before and after
  double final_cost = 0.0;
  bool converged = false;     // a tolerance was met (not the iteration limit)
};

// Residual of one edge: weight * Log(to_from_from^-1 * T_to * T_from^-1), the
// se(3) tangent (rho, omega) of the disagreement, expressed in camera `to`.
// Zero exactly when the poses agree with the measurement.
Eigen::Matrix<double, 6, 1> PoseGraphResidual(const PoseGraphEdge& edge, const SE3d& to_cam_from_world,
                                              const SE3d& from_cam_from_world);

// Optimises the non-fixed poses in place. Poses no edge touches stay as they
// are. Throws dlslam::Error when the graph is malformed: sizes of
// cam_from_world and fixed differ, an edge index is out of range or an edge
// links a pose to itself, a weight is not positive and finite, or no pose is
// fixed while some edge exists (the solution would float freely).
PoseGraphSummary OptimizePoseGraph(PoseGraph* graph, const PoseGraphOptions& options = {});

}  // namespace dlslam

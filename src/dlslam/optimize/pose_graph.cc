#include "dlslam/optimize/pose_graph.h"

#include <ceres/ceres.h>
#include <ceres/product_manifold.h>

#include <array>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam {

void PoseGraphOptions::Check() const {
  DLSLAM_CHECK_GE(max_iterations, 0, "pose graph max_iterations");
  DLSLAM_CHECK(function_tolerance >= 0 && function_tolerance < 1, "pose graph function_tolerance {} outside [0, 1)",
               function_tolerance);
  DLSLAM_CHECK(gradient_tolerance >= 0, "pose graph gradient_tolerance {} is negative", gradient_tolerance);
  DLSLAM_CHECK(parameter_tolerance >= 0, "pose graph parameter_tolerance {} is negative", parameter_tolerance);
  DLSLAM_CHECK_GT(threads, 0, "pose graph threads");
}

namespace {

// Pose parameter block: quaternion (x, y, z, w, Eigen's storage order) then
// translation of cam_from_world.
using PoseBlock = std::array<double, 7>;

template <typename T>
SE3<T> PoseFromBlock(const T* block) {
  return SE3<T>(Eigen::Quaternion<T>(block[3], block[0], block[1], block[2]),
                Eigen::Matrix<T, 3, 1>(block[4], block[5], block[6]));
}

struct EdgeError {
  EdgeError(const SE3d& to_from_from, double edge_weight) : from_from_to(to_from_from.Inverse()), weight(edge_weight) {}

  template <typename T>
  bool operator()(const T* to_block, const T* from_block, T* residual) const {
    const SE3<T> error = from_from_to.cast<T>() * PoseFromBlock(to_block) * PoseFromBlock(from_block).Inverse();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> out(residual);
    out = T(weight) * error.Log();
    return true;
  }

  SE3d from_from_to;  // the measurement, inverted once
  double weight;
};

void CheckGraph(const PoseGraph& graph) {
  const int n = static_cast<int>(graph.cam_from_world.size());
  DLSLAM_CHECK_EQ(graph.cam_from_world.size(), graph.fixed.size(), "pose graph: cam_from_world and fixed sizes differ");
  for (std::size_t e = 0; e < graph.edges.size(); ++e) {
    const PoseGraphEdge& edge = graph.edges[e];
    DLSLAM_CHECK(edge.from >= 0 && edge.from < n && edge.to >= 0 && edge.to < n,
                 "pose graph edge {} links poses {} -> {}, but there are {} poses", e, edge.from, edge.to, n);
    DLSLAM_CHECK(edge.from != edge.to, "pose graph edge {} links pose {} to itself", e, edge.from);
    DLSLAM_CHECK(std::isfinite(edge.weight) && edge.weight > 0, "pose graph edge {} has weight {} (must be > 0)", e,
                 edge.weight);
  }
  if (graph.edges.empty()) return;
  bool any_fixed = false;
  for (const bool f : graph.fixed) any_fixed = any_fixed || f;
  DLSLAM_CHECK(any_fixed, "pose graph of {} poses and {} edges has no fixed pose: the solution would float freely",
               n, graph.edges.size());
}

}  // namespace

Eigen::Matrix<double, 6, 1> PoseGraphResidual(const PoseGraphEdge& edge, const SE3d& to_cam_from_world,
                                              const SE3d& from_cam_from_world) {
  return edge.weight * (edge.to_from_from.Inverse() * to_cam_from_world * from_cam_from_world.Inverse()).Log();
}

PoseGraphSummary OptimizePoseGraph(PoseGraph* graph, const PoseGraphOptions& options) {
  options.Check();
  DLSLAM_CHECK(graph != nullptr, "pose graph is null");
  CheckGraph(*graph);
  PoseGraphSummary summary;
  if (graph->edges.empty()) {
    summary.converged = true;
    return summary;
  }

  std::vector<PoseBlock> blocks(graph->cam_from_world.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Eigen::Quaterniond& q = graph->cam_from_world[i].unit_quaternion();
    const Eigen::Vector3d& t = graph->cam_from_world[i].translation();
    blocks[i] = {q.x(), q.y(), q.z(), q.w(), t.x(), t.y(), t.z()};
  }

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>> pose_manifold;
  for (const PoseGraphEdge& edge : graph->edges) {
    auto* cost = new ceres::AutoDiffCostFunction<EdgeError, 6, 7, 7>(new EdgeError(edge.to_from_from, edge.weight));
    problem.AddResidualBlock(cost, nullptr, blocks[edge.to].data(), blocks[edge.from].data());
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!problem.HasParameterBlock(blocks[i].data())) continue;
    problem.SetManifold(blocks[i].data(), &pose_manifold);
    if (graph->fixed[i]) problem.SetParameterBlockConstant(blocks[i].data());
  }

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.num_threads = options.threads;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary s;
  ceres::Solve(solver_options, &problem, &s);
  DLSLAM_CHECK(s.IsSolutionUsable(), "pose graph optimisation failed: {}", s.message);

  summary.iterations = s.num_successful_steps + s.num_unsuccessful_steps;
  summary.initial_cost = s.initial_cost;
  summary.final_cost = s.final_cost;
  summary.converged = s.termination_type == ceres::CONVERGENCE;
  // Only poses the solver moved are written back: the rest stay bit-exact.
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!graph->fixed[i] && problem.HasParameterBlock(blocks[i].data())) {
      graph->cam_from_world[i] = PoseFromBlock(blocks[i].data());
    }
  }
  return summary;
}

}  // namespace dlslam

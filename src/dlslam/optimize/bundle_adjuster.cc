#include "dlslam/optimize/bundle_adjuster.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <array>
#include <atomic>
#include <cmath>

#include "dlslam/optimize/pose_optimizer.h"
#include "dlslam/util/check.h"

namespace dlslam {

void BundleAdjusterOptions::Check() const {
  DLSLAM_CHECK_GE(first_pass_iterations, 0);
  DLSLAM_CHECK_GE(second_pass_iterations, 0);
  DLSLAM_CHECK_GT(chi2_mono, 0.0);
  DLSLAM_CHECK_GT(chi2_stereo, 0.0);
  DLSLAM_CHECK_GT(threads, 0);
  DLSLAM_CHECK(function_tolerance >= 0 && function_tolerance < 1, "function_tolerance {} outside [0, 1)",
               function_tolerance);
}

const char* ToString(BundleSolver solver) {
  switch (solver) {
    case BundleSolver::kCeres: return "ceres";
    case BundleSolver::kLm: return "lm";
  }
  return "?";
}

BundleSolver ParseBundleSolver(const std::string& text) {
  if (text == "ceres") return BundleSolver::kCeres;
  if (text == "lm") return BundleSolver::kLm;
  throw Error(fmt::format("unknown bundle solver '{}' (expected ceres or lm)", text));
}

BundleSummary SolveBundle(BundleProblem* problem, const BundleAdjusterOptions& options) {
  return options.solver == BundleSolver::kCeres ? SolveBundleCeres(problem, options) : SolveBundleLm(problem, options);
}

double ObservationChi2(const BundleProblem& problem, const BundleProblem::Observation& o) {
  PoseObservation po;
  po.point_world = problem.points[o.point];
  po.pixel = o.pixel;
  po.right_u = o.right_u;
  ObservationLinearization l;
  if (!LinearizeObservation(problem.camera, problem.poses[o.pose].cam_from_world, po, false, &l)) return INFINITY;
  return o.information * l.residual.head(l.rows).squaredNorm();
}

namespace {

// Ends a Ceres solve between iterations once the abort flag is set. It ends
// it as USER_SUCCESS, not SOLVER_ABORT: an aborted Ceres solve does not
// write its parameters back, which would throw away the pass's progress so
// far; terminating keeps the last accepted (best) state.
class AbortCallback : public ceres::IterationCallback {
 public:
  AbortCallback(const std::atomic<bool>* abort, bool* aborted) : abort_(abort), aborted_(aborted) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    if (!abort_->load(std::memory_order_relaxed)) return ceres::SOLVER_CONTINUE;
    *aborted_ = true;
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }

 private:
  const std::atomic<bool>* abort_;
  bool* aborted_;
};

// Reprojection error of a world point in a camera, whitened by the
// observation's information. Pose parameters: quaternion (x, y, z, w, Eigen
// order) and translation of cam_from_world.
struct ReprojectionError {
  ReprojectionError(const CameraIntrinsics& c, const BundleProblem::Observation& o)
      : fx(c.fx), fy(c.fy), cx(c.cx), cy(c.cy), bf(c.bf), u(o.pixel.x()), v(o.pixel.y()), ur(o.right_u),
        sqrt_info(std::sqrt(o.information)) {}

  template <typename T>
  bool operator()(const T* q, const T* t, const T* point, T* residual) const {
    const Eigen::Quaternion<T> rotation(q[3], q[0], q[1], q[2]);
    const Eigen::Matrix<T, 3, 1> p =
        rotation * Eigen::Map<const Eigen::Matrix<T, 3, 1>>(point) + Eigen::Map<const Eigen::Matrix<T, 3, 1>>(t);
    const T inv_z = T(1) / p.z();
    const T pu = T(fx) * p.x() * inv_z + T(cx);
    residual[0] = T(sqrt_info) * (T(u) - pu);
    residual[1] = T(sqrt_info) * (T(v) - (T(fy) * p.y() * inv_z + T(cy)));
    if (ur >= 0) residual[2] = T(sqrt_info) * (T(ur) - (pu - T(bf) * inv_z));
    return true;
  }

  double fx, fy, cx, cy, bf, u, v, ur, sqrt_info;
};

ceres::CostFunction* MakeCost(const CameraIntrinsics& camera, const BundleProblem::Observation& o) {
  if (o.right_u >= 0) {
    return new ceres::AutoDiffCostFunction<ReprojectionError, 3, 4, 3, 3>(new ReprojectionError(camera, o));
  }
  return new ceres::AutoDiffCostFunction<ReprojectionError, 2, 4, 3, 3>(new ReprojectionError(camera, o));
}

double Chi2(const BundleProblem& problem, const BundleProblem::Observation& o,
            const std::vector<std::array<double, 7>>& poses) {
  const ReprojectionError error(problem.camera, o);
  double r[3] = {0, 0, 0};
  const auto& p = poses[o.pose];
  error(p.data(), p.data() + 4, problem.points[o.point].data(), r);
  const Eigen::Vector3d pc = Eigen::Quaterniond(p[3], p[0], p[1], p[2]) * problem.points[o.point] +
                             Eigen::Vector3d(p[4], p[5], p[6]);
  if (pc.z() <= 0) return INFINITY;
  return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

}  // namespace

BundleSummary SolveBundleCeres(BundleProblem* problem, const BundleAdjusterOptions& options) {
  options.Check();
  problem->camera.Check();
  BundleSummary summary;
  summary.outlier.assign(problem->observations.size(), false);
  if (problem->observations.empty()) return summary;

  // Ceres works on raw arrays: quaternion (x, y, z, w) then translation.
  std::vector<std::array<double, 7>> poses(problem->poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Quaterniond& q = problem->poses[i].cam_from_world.unit_quaternion();
    const Eigen::Vector3d& t = problem->poses[i].cam_from_world.translation();
    poses[i] = {q.x(), q.y(), q.z(), q.w(), t.x(), t.y(), t.z()};
  }

  const auto solve = [&](int iterations, bool robust, const std::vector<bool>& skip) {
    ceres::Problem::Options problem_options;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem ceres_problem(problem_options);
    ceres::EigenQuaternionManifold quaternion_manifold;
    for (std::size_t k = 0; k < problem->observations.size(); ++k) {
      if (skip[k]) continue;
      const auto& o = problem->observations[k];
      ceres::LossFunction* loss =
          robust ? new ceres::HuberLoss(std::sqrt(o.right_u >= 0 ? options.chi2_stereo : options.chi2_mono))
                 : nullptr;
      double* pose = poses[o.pose].data();
      ceres_problem.AddResidualBlock(MakeCost(problem->camera, o), loss, pose, pose + 4,
                                     problem->points[o.point].data());
    }
    for (std::size_t i = 0; i < poses.size(); ++i) {
      double* pose = poses[i].data();
      if (!ceres_problem.HasParameterBlock(pose)) continue;
      ceres_problem.SetManifold(pose, &quaternion_manifold);
      if (problem->poses[i].fixed) {
        ceres_problem.SetParameterBlockConstant(pose);
        ceres_problem.SetParameterBlockConstant(pose + 4);
      }
    }
    ceres::Solver::Options solver_options;
    solver_options.linear_solver_type = ceres::SPARSE_SCHUR;
    solver_options.max_num_iterations = iterations;
    solver_options.num_threads = options.threads;
    solver_options.logging_type = ceres::SILENT;
    solver_options.function_tolerance = options.function_tolerance;
    AbortCallback abort_callback(options.abort, &summary.aborted);
    if (options.abort != nullptr) solver_options.callbacks.push_back(&abort_callback);
    ceres::Solver::Summary s;
    ceres::Solve(solver_options, &ceres_problem, &s);
    summary.iterations += static_cast<int>(s.iterations.size());
    if (summary.initial_cost == 0.0) summary.initial_cost = s.initial_cost;
    summary.final_cost = s.final_cost;
  };

  std::vector<bool> none(problem->observations.size(), false);
  if (options.first_pass_iterations > 0) solve(options.first_pass_iterations, true, none);
  for (std::size_t k = 0; k < problem->observations.size(); ++k) {
    const auto& o = problem->observations[k];
    summary.outlier[k] = Chi2(*problem, o, poses) > (o.right_u >= 0 ? options.chi2_stereo : options.chi2_mono);
  }
  if (options.second_pass_iterations > 0 && !summary.aborted) solve(options.second_pass_iterations, false, summary.outlier);
  summary.outliers = 0;
  for (std::size_t k = 0; k < problem->observations.size(); ++k) {
    const auto& o = problem->observations[k];
    summary.outlier[k] = Chi2(*problem, o, poses) > (o.right_u >= 0 ? options.chi2_stereo : options.chi2_mono);
    summary.outliers += summary.outlier[k];
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto& p = poses[i];
    problem->poses[i].cam_from_world =
        SE3d(Eigen::Quaterniond(p[3], p[0], p[1], p[2]), Eigen::Vector3d(p[4], p[5], p[6]));
  }
  return summary;
}

}  // namespace dlslam

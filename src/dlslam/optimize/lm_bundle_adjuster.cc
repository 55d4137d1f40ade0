// Our own sparse Levenberg-Marquardt for bundle adjustment: the same problem,
// robust kernel and two-pass scheme as the Ceres solver (bundle_adjuster.cc),
// written for the shape of local bundles: a few dozen poses, thousands of
// points. Each iteration linearises every observation once (analytic
// Jacobians of pose_optimizer.h), eliminates the points (3x3 blocks) by the
// Schur complement and solves the dense reduced camera system (6 per free
// pose) with a Cholesky factorisation. The Huber kernel is applied by
// iteratively reweighted least squares, whose fixed point is the Huber
// minimum that Ceres finds too.

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "dlslam/optimize/bundle_adjuster.h"
#include "dlslam/optimize/pose_optimizer.h"
#include "dlslam/util/check.h"

namespace dlslam {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix63d = Eigen::Matrix<double, 6, 3>;

// The whitened squared error of an observation (the caller applies `information`).
bool Linearize(const BundleProblem& problem, const BundleProblem::Observation& o, bool with_jacobian,
               ObservationLinearization* l) {
  PoseObservation po;
  po.point_world = problem.points[o.point];
  po.pixel = o.pixel;
  po.right_u = o.right_u;
  return LinearizeObservation(problem.camera, problem.poses[o.pose].cam_from_world, po, with_jacobian, l);
}

class LmSolver {
 public:
  LmSolver(BundleProblem* problem, const BundleAdjusterOptions& options) : p_(*problem), options_(options) {
    free_index_.assign(p_.poses.size(), -1);
    for (std::size_t i = 0; i < p_.poses.size(); ++i) {
      if (!p_.poses[i].fixed) free_index_[i] = num_free_++;
    }
    by_point_.resize(p_.points.size());
    for (std::size_t k = 0; k < p_.observations.size(); ++k) by_point_[p_.observations[k].point].push_back(k);
  }

  // One pass of at most `iterations` iterations over the observations not in
  // `skip`. Returns the iterations run; the costs are 0.5 * sum rho.
  // Stops before an iteration when options.abort is set (and says so in *aborted).
  int Run(int iterations, bool robust, const std::vector<bool>& skip, double* initial_cost, double* final_cost,
          bool* aborted) {
    robust_ = robust;
    skip_ = &skip;
    double cost = Cost();
    *initial_cost = cost;
    double lambda = 1e-4;
    int done = 0;
    for (; done < iterations; ++done) {
      if (options_.abort != nullptr && options_.abort->load(std::memory_order_relaxed)) {
        *aborted = true;
        break;
      }
      BuildNormalEquations();
      bool accepted = false;
      double previous = cost;
      for (int attempt = 0; attempt < 10 && !accepted; ++attempt) {
        if (!SolveStep(lambda)) {
          lambda *= 10;
          continue;
        }
        const std::vector<SE3d> old_poses = SavePoses();
        const std::vector<Eigen::Vector3d> old_points = p_.points;
        ApplyStep();
        const double new_cost = Cost();
        if (new_cost < cost) {
          cost = new_cost;
          lambda = std::max(lambda / 10, 1e-9);
          accepted = true;
        } else {
          RestorePoses(old_poses);
          p_.points = old_points;
          lambda *= 10;
        }
      }
      if (!accepted) break;
      if (previous - cost <= options_.function_tolerance * previous) {
        ++done;
        break;
      }
    }
    *final_cost = cost;
    return done;
  }

 private:
  double Chi2Limit(const ObservationLinearization& l) const {
    return l.rows == 3 ? options_.chi2_stereo : options_.chi2_mono;
  }

  // 0.5 * sum over active observations of rho(chi2); Huber rho as Ceres:
  // chi2 inside the threshold, 2 delta sqrt(chi2) - delta^2 outside.
  double Cost() const {
    double cost = 0;
    ObservationLinearization l;
    for (std::size_t k = 0; k < p_.observations.size(); ++k) {
      if ((*skip_)[k]) continue;
      const auto& o = p_.observations[k];
      if (!Linearize(p_, o, false, &l)) {
        cost += 1e6;  // behind the camera: heavy but finite, so a step can still leave it
        continue;
      }
      const double chi2 = o.information * l.residual.head(l.rows).squaredNorm();
      const double delta_sq = Chi2Limit(l);
      cost += (!robust_ || chi2 <= delta_sq) ? chi2 : 2 * std::sqrt(delta_sq * chi2) - delta_sq;
    }
    return 0.5 * cost;
  }

  // Gauss-Newton blocks: U (free poses), V (points), W (per observation of a
  // free pose) and the gradients.
  void BuildNormalEquations() {
    U_.assign(num_free_, Matrix6d::Zero());
    gp_.assign(num_free_, Vector6d::Zero());
    V_.assign(p_.points.size(), Eigen::Matrix3d::Zero());
    gl_.assign(p_.points.size(), Eigen::Vector3d::Zero());
    W_.assign(p_.observations.size(), Matrix63d::Zero());
    rows_.assign(p_.points.size(), 0);
    ObservationLinearization l;
    for (std::size_t k = 0; k < p_.observations.size(); ++k) {
      if ((*skip_)[k]) continue;
      const auto& o = p_.observations[k];
      if (!Linearize(p_, o, true, &l)) continue;
      const double chi2 = o.information * l.residual.head(l.rows).squaredNorm();
      const double delta_sq = Chi2Limit(l);
      const double w = o.information * ((robust_ && chi2 > delta_sq) ? std::sqrt(delta_sq / chi2) : 1.0);
      // d(residual)/d(point_world) = d(residual)/d(p_cam) * R; the first three
      // pose columns are d(residual)/d(p_cam) (a translation of the camera frame).
      const Eigen::Matrix3d j_point = l.jacobian.leftCols<3>() * p_.poses[o.pose].cam_from_world.rotationMatrix();
      rows_[o.point] += l.rows;
      V_[o.point].noalias() += w * j_point.transpose() * j_point;
      gl_[o.point].noalias() += w * j_point.transpose() * l.residual;
      const int f = free_index_[o.pose];
      if (f < 0) continue;
      U_[f].noalias() += w * l.jacobian.transpose() * l.jacobian;
      gp_[f].noalias() += w * l.jacobian.transpose() * l.residual;
      W_[k].noalias() = w * l.jacobian.transpose() * j_point;
    }
  }

  // Solves the damped system for the pose and point steps by eliminating the
  // points. Marquardt damping: diagonal scaled by (1 + lambda).
  bool SolveStep(double lambda) {
    const int n = 6 * num_free_;
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    for (int f = 0; f < num_free_; ++f) {
      Matrix6d u = U_[f];
      u.diagonal() += lambda * U_[f].diagonal().cwiseMax(1e-6);
      S.block<6, 6>(6 * f, 6 * f) = u;
      b.segment<6>(6 * f) = -gp_[f];
    }
    v_inv_.assign(p_.points.size(), Eigen::Matrix3d::Zero());
    std::vector<Matrix63d> wv;  // W V^-1 per active free-pose observation of the point
    std::vector<int> slots;     // its free-pose slot
    std::vector<std::size_t> ks;  // its observation index
    for (std::size_t j = 0; j < p_.points.size(); ++j) {
      if (rows_[j] == 0) continue;  // no active observation: the point stays
      Eigen::Matrix3d v = V_[j];
      v.diagonal() += lambda * V_[j].diagonal().cwiseMax(1e-6);
      if (rows_[j] < 3) {
        // One keypoint without depth: free along its ray. A pseudo-inverse
        // keeps it from sliding there on rounding noise (as Ceres' solution,
        // the point then fits its keypoint and leaves the pose alone).
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(v);
        const Eigen::Vector3d values = eig.eigenvalues();
        Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
        for (int r = 0; r < 3; ++r) inverse[r] = values[r] > 1e-6 * values.maxCoeff() ? 1.0 / values[r] : 0.0;
        v_inv_[j] = eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
      } else {
        const Eigen::LLT<Eigen::Matrix3d> llt(v);
        if (llt.info() != Eigen::Success) return false;
        v_inv_[j] = llt.solve(Eigen::Matrix3d::Identity());
      }
      // S -= W V^-1 W^T over pairs of free poses seeing this point; b += W V^-1 gl.
      wv.clear();
      slots.clear();
      ks.clear();
      for (std::size_t k : by_point_[j]) {
        const int f = free_index_[p_.observations[k].pose];
        if (f < 0 || (*skip_)[k]) continue;
        wv.push_back(W_[k] * v_inv_[j]);
        slots.push_back(f);
        ks.push_back(k);
        b.segment<6>(6 * f) += wv.back() * gl_[j];
      }
      for (std::size_t a = 0; a < slots.size(); ++a) {
        for (std::size_t c = a; c < slots.size(); ++c) {
          const Matrix6d block = wv[a] * W_[ks[c]].transpose();
          S.block<6, 6>(6 * slots[a], 6 * slots[c]) -= block;
          if (a != c) S.block<6, 6>(6 * slots[c], 6 * slots[a]) -= block.transpose();
        }
      }
    }
    Eigen::VectorXd dp = Eigen::VectorXd::Zero(n);
    if (n > 0) {
      const Eigen::LLT<Eigen::MatrixXd> llt(S);
      if (llt.info() != Eigen::Success) return false;
      dp = llt.solve(b);
      if (!dp.allFinite()) return false;
    }
    pose_step_.assign(num_free_, Vector6d::Zero());
    for (int f = 0; f < num_free_; ++f) pose_step_[f] = dp.segment<6>(6 * f);
    point_step_.assign(p_.points.size(), Eigen::Vector3d::Zero());
    for (std::size_t j = 0; j < p_.points.size(); ++j) {
      Eigen::Vector3d r = -gl_[j];
      for (std::size_t k : by_point_[j]) {
        const int f = free_index_[p_.observations[k].pose];
        if (f >= 0 && !(*skip_)[k]) r -= W_[k].transpose() * pose_step_[f];
      }
      point_step_[j] = v_inv_[j] * r;
    }
    return true;
  }

  void ApplyStep() {
    for (std::size_t i = 0; i < p_.poses.size(); ++i) {
      if (free_index_[i] < 0) continue;
      p_.poses[i].cam_from_world = SE3d::Exp(pose_step_[free_index_[i]]) * p_.poses[i].cam_from_world;
    }
    for (std::size_t j = 0; j < p_.points.size(); ++j) p_.points[j] += point_step_[j];
  }

  std::vector<SE3d> SavePoses() const {
    std::vector<SE3d> out;
    for (const auto& pose : p_.poses) out.push_back(pose.cam_from_world);
    return out;
  }
  void RestorePoses(const std::vector<SE3d>& poses) {
    for (std::size_t i = 0; i < poses.size(); ++i) p_.poses[i].cam_from_world = poses[i];
  }

  BundleProblem& p_;
  const BundleAdjusterOptions& options_;
  std::vector<int> free_index_;  // per pose: slot among the free poses, -1 if fixed
  int num_free_ = 0;
  std::vector<std::vector<std::size_t>> by_point_;  // observations of each point
  bool robust_ = true;
  const std::vector<bool>* skip_ = nullptr;
  std::vector<Matrix6d> U_;
  std::vector<Vector6d> gp_;
  std::vector<Eigen::Matrix3d> V_, v_inv_;
  std::vector<Eigen::Vector3d> gl_;
  std::vector<Matrix63d> W_;
  std::vector<int> rows_;  // per point: residual rows of its active observations
  std::vector<Vector6d> pose_step_;
  std::vector<Eigen::Vector3d> point_step_;
};

}  // namespace

BundleSummary SolveBundleLm(BundleProblem* problem, const BundleAdjusterOptions& options) {
  options.Check();
  problem->camera.Check();
  BundleSummary summary;
  const std::size_t n = problem->observations.size();
  summary.outlier.assign(n, false);
  if (n == 0) return summary;
  for (const auto& o : problem->observations) {
    DLSLAM_CHECK(o.pose >= 0 && o.pose < static_cast<int>(problem->poses.size()), "observation of pose {}", o.pose);
    DLSLAM_CHECK(o.point >= 0 && o.point < static_cast<int>(problem->points.size()), "observation of point {}", o.point);
  }
  LmSolver solver(problem, options);
  const auto classify = [&] {
    summary.outliers = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const auto& o = problem->observations[k];
      summary.outlier[k] = ObservationChi2(*problem, o) > (o.right_u >= 0 ? options.chi2_stereo : options.chi2_mono);
      summary.outliers += summary.outlier[k];
    }
  };
  bool first = true;
  const auto pass = [&](int iterations, bool robust, const std::vector<bool>& skip) {
    double initial = 0, final_cost = 0;
    summary.iterations += solver.Run(iterations, robust, skip, &initial, &final_cost, &summary.aborted);
    if (first) summary.initial_cost = initial;
    first = false;
    summary.final_cost = final_cost;
  };
  const std::vector<bool> none(n, false);
  if (options.first_pass_iterations > 0) pass(options.first_pass_iterations, true, none);
  classify();
  if (options.second_pass_iterations > 0 && !summary.aborted) pass(options.second_pass_iterations, false, summary.outlier);
  classify();
  return summary;
}

}  // namespace dlslam

// Our own sparse Levenberg-Marquardt for bundle adjustment: the same problem,
// robust kernel and two-pass scheme as the Ceres solver (bundle_adjuster.cc),
// written for the shape of local bundles: a few dozen poses, thousands of
// points. Each iteration linearises every observation once (analytic
// Jacobians of pose_optimizer.h; the pass that costs a step also builds the
// next iteration's system), eliminates the points (3x3 blocks) by the Schur
// complement and solves the dense reduced camera system (6 per free pose)
// with a Cholesky factorisation. The Huber kernel is applied by
// iteratively reweighted least squares, whose fixed point is the Huber
// minimum that Ceres finds too.

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

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

// hat(p) * x: each column of x crossed with p.
inline Eigen::Matrix3d CrossColumns(const Eigen::Vector3d& p, const Eigen::Matrix3d& x) {
  Eigen::Matrix3d out;
  for (int c = 0; c < 3; ++c) out.col(c) = p.cross(x.col(c));
  return out;
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
    Evaluate(&current_);
    double cost = current_.cost;
    *initial_cost = cost;
    double lambda = 1e-4;
    int done = 0;
    for (; done < iterations; ++done) {
      if (options_.abort != nullptr && options_.abort->load(std::memory_order_relaxed)) {
        *aborted = true;
        break;
      }
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
        Evaluate(&candidate_);
        if (candidate_.cost < cost) {
          cost = candidate_.cost;
          std::swap(current_, candidate_);
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
  // The Gauss-Newton system at the current values: blocks U (free poses), V
  // (points), W (per observation of a free pose), the gradients, and the
  // cost 0.5 * sum over active observations of rho(chi2), Huber rho as
  // Ceres: chi2 inside the threshold, 2 delta sqrt(chi2) - delta^2 outside.
  struct NormalSystem {
    std::vector<Matrix6d> U;
    std::vector<Vector6d> gp;
    std::vector<Eigen::Matrix3d> V;
    std::vector<Eigen::Vector3d> gl;
    std::vector<Matrix63d> W;  // read only for active observations of free poses
    std::vector<int> rows;     // per point: residual rows of its active observations
    double cost = 0;
  };

  void Evaluate(NormalSystem* s) {
    rotations_.resize(p_.poses.size());
    for (std::size_t i = 0; i < p_.poses.size(); ++i) rotations_[i] = p_.poses[i].cam_from_world.rotationMatrix();
    s->U.assign(num_free_, Matrix6d::Zero());
    s->gp.assign(num_free_, Vector6d::Zero());
    s->V.assign(p_.points.size(), Eigen::Matrix3d::Zero());
    s->gl.assign(p_.points.size(), Eigen::Vector3d::Zero());
    s->W.resize(p_.observations.size());
    s->rows.assign(p_.points.size(), 0);
    double cost = 0;
    ObservationLinearization l;
    for (std::size_t k = 0; k < p_.observations.size(); ++k) {
      if ((*skip_)[k]) continue;
      const auto& o = p_.observations[k];
      const Eigen::Matrix3d& rotation = rotations_[o.pose];
      const Eigen::Vector3d p = rotation * p_.points[o.point] + p_.poses[o.pose].cam_from_world.translation();
      if (!LinearizeCameraPoint(p_.camera, p, o.pixel, o.right_u, false, &l)) {
        cost += 1e6;  // behind the camera: heavy but finite, so a step can still leave it
        s->W[k].setZero();
        continue;
      }
      const double chi2 = o.information * l.residual.head(l.rows).squaredNorm();
      const double delta_sq = l.rows == 3 ? options_.chi2_stereo : options_.chi2_mono;
      const bool inside = !robust_ || chi2 <= delta_sq;
      cost += inside ? chi2 : 2 * std::sqrt(delta_sq * chi2) - delta_sq;
      const double w = o.information * (inside ? 1.0 : std::sqrt(delta_sq / chi2));
      // With A = d(projection)/d(p) the residual's Jacobians are -A [I, -hat(p)]
      // for the pose and -A R for the point, so every block comes from
      // M = w A^T A and q = w A^T e (half the products of forming J^T J):
      // U += [M, N^T; N, hat(p) N^T] with N = hat(p) M, W = [M R; hat(p) M R],
      // V += R^T M R, gradients -[q; p x q] and -R^T q.
      const Eigen::Matrix3d a = ProjectionJacobian(p_.camera, p, l.rows);
      const Eigen::Matrix3d m = w * (a.transpose() * a);
      const Eigen::Vector3d q = w * (a.transpose() * l.residual);
      const Eigen::Matrix3d mr = m * rotation;
      s->rows[o.point] += l.rows;
      s->V[o.point].noalias() += rotation.transpose() * mr;
      s->gl[o.point].noalias() -= rotation.transpose() * q;
      const int f = free_index_[o.pose];
      if (f < 0) continue;
      const Eigen::Matrix3d n = CrossColumns(p, m);
      Matrix6d& u = s->U[f];
      u.topLeftCorner<3, 3>() += m;
      u.bottomLeftCorner<3, 3>() += n;
      u.topRightCorner<3, 3>() += n.transpose();
      u.bottomRightCorner<3, 3>() += CrossColumns(p, n.transpose());
      s->gp[f].head<3>() -= q;
      s->gp[f].tail<3>() -= p.cross(q);
      s->W[k].topRows<3>() = mr;
      s->W[k].bottomRows<3>() = CrossColumns(p, mr);
    }
    s->cost = 0.5 * cost;
  }

  // Solves the damped system for the pose and point steps by eliminating the
  // points. Marquardt damping: diagonal scaled by (1 + lambda).
  bool SolveStep(double lambda) {
    const NormalSystem& sys = current_;
    const int n = 6 * num_free_;
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    for (int f = 0; f < num_free_; ++f) {
      Matrix6d u = sys.U[f];
      u.diagonal() += lambda * sys.U[f].diagonal().cwiseMax(1e-6);
      S.block<6, 6>(6 * f, 6 * f) = u;
      b.segment<6>(6 * f) = -sys.gp[f];
    }
    v_inv_.assign(p_.points.size(), Eigen::Matrix3d::Zero());
    std::vector<Matrix63d> wv;  // W V^-1 per active free-pose observation of the point
    std::vector<int> slots;     // its free-pose slot
    std::vector<std::size_t> ks;  // its observation index
    for (std::size_t j = 0; j < p_.points.size(); ++j) {
      if (sys.rows[j] == 0) continue;  // no active observation: the point stays
      Eigen::Matrix3d v = sys.V[j];
      v.diagonal() += lambda * sys.V[j].diagonal().cwiseMax(1e-6);
      if (sys.rows[j] < 3) {
        // One keypoint without depth: free along its ray. A pseudo-inverse
        // keeps it from sliding there on rounding noise (as Ceres' solution,
        // the point then fits its keypoint and leaves the pose alone).
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(v);
        const Eigen::Vector3d values = eig.eigenvalues();
        Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
        for (int r = 0; r < 3; ++r) inverse[r] = values[r] > 1e-6 * values.maxCoeff() ? 1.0 / values[r] : 0.0;
        v_inv_[j] = eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
      } else {
        // Positive definite (checked by the factorisation), then the 3x3
        // inverse in closed form: a triangular solve costs twice as much.
        if (Eigen::LLT<Eigen::Matrix3d>(v).info() != Eigen::Success) return false;
        v_inv_[j] = v.inverse();
      }
      // S -= W V^-1 W^T over pairs of free poses seeing this point; b += W V^-1 gl.
      wv.clear();
      slots.clear();
      ks.clear();
      for (std::size_t k : by_point_[j]) {
        const int f = free_index_[p_.observations[k].pose];
        if (f < 0 || (*skip_)[k]) continue;
        wv.push_back(sys.W[k] * v_inv_[j]);
        slots.push_back(f);
        ks.push_back(k);
        b.segment<6>(6 * f) += wv.back() * sys.gl[j];
      }
      // Only S's lower triangle: the Cholesky factorisation reads no more.
      for (std::size_t a = 0; a < slots.size(); ++a) {
        for (std::size_t c = a; c < slots.size(); ++c) {
          // Block (row, col) = W_row V^-1 W_col^T with row >= col.
          const std::size_t hi = slots[a] >= slots[c] ? a : c, lo = hi == a ? c : a;
          auto target = S.block<6, 6>(6 * slots[hi], 6 * slots[lo]);
          if (a == c || slots[a] != slots[c]) {
            target.noalias() -= wv[hi] * sys.W[ks[lo]].transpose();
          } else {  // two observations of the point in one keyframe
            const Matrix6d block = wv[hi] * sys.W[ks[lo]].transpose();
            target -= block + block.transpose();
          }
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
      Eigen::Vector3d r = -sys.gl[j];
      for (std::size_t k : by_point_[j]) {
        const int f = free_index_[p_.observations[k].pose];
        if (f >= 0 && !(*skip_)[k]) r -= sys.W[k].transpose() * pose_step_[f];
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
  NormalSystem current_;    // at the current values
  NormalSystem candidate_;  // at the values after a step, until it is accepted
  std::vector<Eigen::Matrix3d> rotations_;  // per pose, for Evaluate
  std::vector<Eigen::Matrix3d> v_inv_;
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

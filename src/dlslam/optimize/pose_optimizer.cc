#include "dlslam/optimize/pose_optimizer.h"

#include <Eigen/Cholesky>

#include <array>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam {

void PoseOptimizerOptions::Check() const {
  DLSLAM_CHECK_GT(rounds, 0);
  DLSLAM_CHECK_GT(iterations_per_round, 0);
  DLSLAM_CHECK_GT(chi2_mono, 0.0);
  DLSLAM_CHECK_GT(chi2_stereo, 0.0);
  DLSLAM_CHECK_GE(min_step, 0.0);
}

namespace {
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Linearization = ObservationLinearization;

// The residual of an observation of the camera-frame point p; false when p
// is not in front of the camera.
bool Residual(const CameraIntrinsics& camera, const Eigen::Vector3d& p, const Eigen::Vector2d& pixel,
              double right_u, Linearization* out) {
  if (p.z() <= 1e-6) return false;
  const double inv_z = 1.0 / p.z();
  const double u = camera.fx * p.x() * inv_z + camera.cx;
  const double v = camera.fy * p.y() * inv_z + camera.cy;
  out->rows = right_u >= 0 ? 3 : 2;
  out->residual.x() = pixel.x() - u;
  out->residual.y() = pixel.y() - v;
  out->residual.z() = out->rows == 3 ? right_u - (u - camera.bf * inv_z) : 0.0;
  return true;
}
bool Residual(const CameraIntrinsics& camera, const Eigen::Vector3d& p, const PoseObservation& obs,
              Linearization* out) {
  return Residual(camera, p, obs.pixel, obs.right_u, out);
}

// d(residual) / d(delta) at the camera-frame point p: -d(u, v, u_right) /
// d(p) times d(p) / d(delta) = [I, -hat(p)], multiplied out: each row a of
// the projection's derivative gives (-a, a x p).
void Jacobian(const CameraIntrinsics& camera, const Eigen::Vector3d& p, int rows,
              Eigen::Matrix<double, 3, 6>* jacobian) {
  const Eigen::Matrix3d a = ProjectionJacobian(camera, p, rows);
  for (int r = 0; r < 3; ++r) {
    jacobian->row(r) << -a(r, 0), -a(r, 1), -a(r, 2), a(r, 1) * p.z() - a(r, 2) * p.y(),
        a(r, 2) * p.x() - a(r, 0) * p.z(), a(r, 0) * p.y() - a(r, 1) * p.x();
  }
}

}  // namespace

Eigen::Matrix3d ProjectionJacobian(const CameraIntrinsics& camera, const Eigen::Vector3d& p, int rows) {
  const double inv_z = 1.0 / p.z();
  const double inv_z2 = inv_z * inv_z;
  const double du_dz = -camera.fx * p.x() * inv_z2;
  const double dv_dz = -camera.fy * p.y() * inv_z2;
  Eigen::Matrix3d a;
  a << camera.fx * inv_z, 0, du_dz,  //
      0, camera.fy * inv_z, dv_dz,   //
      0, 0, 0;
  if (rows == 3) a.row(2) << camera.fx * inv_z, 0, du_dz + camera.bf * inv_z2;
  return a;
}

bool LinearizeObservation(const CameraIntrinsics& camera, const SE3d& cam_from_world,
                          const PoseObservation& obs, bool with_jacobian, Linearization* out) {
  return LinearizeCameraPoint(camera, cam_from_world * obs.point_world, obs.pixel, obs.right_u, with_jacobian, out);
}

bool LinearizeCameraPoint(const CameraIntrinsics& camera, const Eigen::Vector3d& point_cam,
                          const Eigen::Vector2d& pixel, double right_u, bool with_jacobian, Linearization* out) {
  if (!Residual(camera, point_cam, pixel, right_u, out)) return false;
  if (with_jacobian) Jacobian(camera, point_cam, out->rows, &out->jacobian);
  return true;
}

namespace {

double Chi2(const Linearization& l, double information) {
  return information * l.residual.head(l.rows).squaredNorm();
}

// Huber weight for IRLS on chi2 = e^T Omega e with threshold delta^2.
double HuberWeight(double chi2, double delta_sq) {
  return chi2 <= delta_sq ? 1.0 : std::sqrt(delta_sq / chi2);
}

// The robust cost at a pose and the Gauss-Newton system around it, in one
// pass: the cost that accepts a step is then also the next iteration's
// linearisation.
struct NormalEquations {
  Matrix6d H = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  double cost = 0;
};

// The pose's rotation as a matrix: one conversion per pass instead of a
// quaternion rotation per observation (the tracker runs ~17 passes over ~340
// matches per call, three calls a frame).
struct PoseMatrix {
  explicit PoseMatrix(const SE3d& pose) : rotation(pose.rotationMatrix()), translation(pose.translation()) {}
  Eigen::Vector3d operator*(const Eigen::Vector3d& x) const { return rotation * x + translation; }
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation;
};

NormalEquations Linearize(const CameraIntrinsics& camera, const SE3d& pose,
                          const std::vector<PoseObservation>& observations, const std::vector<bool>& active,
                          const PoseOptimizerOptions& options, bool robust) {
  NormalEquations eq;
  const PoseMatrix cam_from_world(pose);
  // H's upper triangle, row by row (21 entries): half the work of J^T J.
  std::array<double, 21> h{};
  Linearization l;
  for (std::size_t i = 0; i < observations.size(); ++i) {
    if (!active[i]) continue;
    const Eigen::Vector3d p = cam_from_world * observations[i].point_world;
    if (!Residual(camera, p, observations[i], &l)) {
      eq.cost += 1e6;  // behind the camera: a heavy but finite penalty
      continue;
    }
    Jacobian(camera, p, l.rows, &l.jacobian);
    const double info = observations[i].information;
    const double chi2 = Chi2(l, info);
    const double delta_sq = l.rows == 3 ? options.chi2_stereo : options.chi2_mono;
    const bool inside = !robust || chi2 <= delta_sq;
    // Huber cost (times 2): chi2 inside, 2 delta sqrt(chi2) - delta^2 outside.
    eq.cost += inside ? chi2 : 2 * std::sqrt(delta_sq * chi2) - delta_sq;
    const double w = inside ? info : HuberWeight(chi2, delta_sq) * info;
    for (int r = 0; r < l.rows; ++r) {
      const auto j = l.jacobian.row(r);
      std::size_t k = 0;
      for (int a = 0; a < 6; ++a) {
        const double wa = w * j(a);
        for (int b = a; b < 6; ++b) h[k++] += wa * j(b);
        eq.g(a) += wa * l.residual(r);
      }
    }
  }
  std::size_t k = 0;
  for (int a = 0; a < 6; ++a) {
    for (int b = a; b < 6; ++b) eq.H(a, b) = eq.H(b, a) = h[k++];
  }
  return eq;
}

// Levenberg-Marquardt iterations over the active observations.
SE3d RunIterations(const CameraIntrinsics& camera, SE3d pose, const std::vector<PoseObservation>& observations,
                   const std::vector<bool>& active, const PoseOptimizerOptions& options, bool robust) {
  double lambda = 1e-4;
  NormalEquations eq = Linearize(camera, pose, observations, active, options, robust);
  for (int it = 0; it < options.iterations_per_round; ++it) {
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Matrix6d damped = eq.H;
      damped.diagonal() += lambda * eq.H.diagonal().cwiseMax(1e-9);
      const Vector6d step = damped.ldlt().solve(-eq.g);
      if (!step.allFinite()) break;
      // At the minimum every step fails to lower the cost by rounding alone:
      // a step this small means converged (taken unchecked: it cannot hurt),
      // not "try a larger lambda".
      const SE3d candidate = SE3d::Exp(step) * pose;
      if (step.norm() < options.min_step) return candidate;
      NormalEquations at_candidate = Linearize(camera, candidate, observations, active, options, robust);
      if (at_candidate.cost < eq.cost) {
        pose = candidate;
        eq = at_candidate;
        lambda = std::max(lambda / 10, 1e-10);
        improved = true;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  return pose;
}

}  // namespace

PoseOptimizationResult OptimizePose(const CameraIntrinsics& camera, const SE3d& initial_cam_from_world,
                                    const std::vector<PoseObservation>& observations,
                                    const PoseOptimizerOptions& options) {
  options.Check();
  PoseOptimizationResult result;
  result.cam_from_world = initial_cam_from_world;
  result.inliers.assign(observations.size(), false);
  if (observations.size() < 3) return result;

  std::vector<bool> active(observations.size(), true);
  Linearization l;
  for (int round = 0; round < options.rounds; ++round) {
    const bool robust = round + 1 < options.rounds || options.robust_last_round;
    result.cam_from_world =
        RunIterations(camera, result.cam_from_world, observations, active, options, robust);
    // Classify every observation, outliers included: a point rejected under a
    // bad early pose may fit the refined one.
    result.num_inliers = 0;
    result.final_chi2 = 0;
    const PoseMatrix cam_from_world(result.cam_from_world);
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const bool ok = Residual(camera, cam_from_world * observations[i].point_world, observations[i], &l);
      const double chi2 = ok ? Chi2(l, observations[i].information) : INFINITY;
      const double limit = ok && l.rows == 3 ? options.chi2_stereo : options.chi2_mono;
      active[i] = chi2 <= limit;
      if (active[i]) {
        ++result.num_inliers;
        result.final_chi2 += chi2;
      }
    }
    if (result.num_inliers < 3) break;
  }
  result.inliers = active;
  return result;
}

}  // namespace dlslam

#pragma once
// Motion-only bundle adjustment: the camera pose that best explains the
// observed keypoints of known 3D points, robust to wrong matches.
//
// The scheme of ORB-SLAM's pose optimisation, written as a small
// Levenberg-Marquardt on SE(3): several rounds; in each, Huber-weighted
// iterations, then every observation is classified by its chi-square error
// (2 dof for a monocular keypoint, 3 dof with the RGB-D virtual right
// coordinate) and outliers sit out the next round (they may come back). The
// last round drops the robust kernel.

#include <Eigen/Core>

#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam {

// One 2D keypoint matched to a 3D point in the world.
struct PoseObservation {
  Eigen::Vector3d point_world = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();         // undistorted keypoint [px]
  // Virtual right-image u [px] = u - bf / depth for keypoints with depth;
  // negative when the keypoint has no depth (monocular observation).
  double right_u = -1.0;
  // 1 / sigma^2 of the keypoint's pyramid level (scale_factor^(2 * octave)).
  double information = 1.0;
};

struct PoseOptimizerOptions {
  // Rounds of outlier classification (ORB-SLAM: 4).
  int rounds = 4;
  // Levenberg-Marquardt iterations per round (ORB-SLAM: 10).
  int iterations_per_round = 10;
  // Chi-square thresholds at 95 % for 2 dof (monocular) and 3 dof (RGB-D).
  double chi2_mono = 5.991;
  double chi2_stereo = 7.815;
  // Drop the Huber kernel in the last round, as ORB-SLAM does.
  bool robust_last_round = false;
  // Converged when the update is smaller than this [rad or m]: 1e-8 m is
  // far below what pixels resolve, and without it every round spends its
  // iterations retrying steps that only rounding keeps from helping.
  double min_step = 1e-8;

  void Check() const;
};

struct PoseOptimizationResult {
  SE3d cam_from_world;
  std::vector<bool> inliers;  // per observation, after the last round
  int num_inliers = 0;
  double final_chi2 = 0.0;  // sum over inliers, information-weighted
};

// Residual (observed - predicted: u, v and, for RGB-D observations, the
// virtual right u) of one observation and its Jacobian with respect to a left
// perturbation exp(delta) * cam_from_world, delta = (rho, omega). Rows beyond
// `rows` are zero. Returns false when the point is not in front of the camera.
struct ObservationLinearization {
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 6> jacobian = Eigen::Matrix<double, 3, 6>::Zero();
  int rows = 2;
};
bool LinearizeObservation(const CameraIntrinsics& camera, const SE3d& cam_from_world,
                          const PoseObservation& observation, bool with_jacobian,
                          ObservationLinearization* out);
// The same for a point already in the camera frame (cam_from_world *
// point_world): bundle adjustment turns each pose into a matrix once per
// pass instead of rotating by its quaternion per observation.
bool LinearizeCameraPoint(const CameraIntrinsics& camera, const Eigen::Vector3d& point_cam,
                          const Eigen::Vector2d& pixel, double right_u, bool with_jacobian,
                          ObservationLinearization* out);
// d(u, v, u_right) / d(point_cam), the projection's derivative at a
// camera-frame point in front of the camera (the residual's is its
// negative); row 2 is zero unless rows == 3.
Eigen::Matrix3d ProjectionJacobian(const CameraIntrinsics& camera, const Eigen::Vector3d& point_cam, int rows);

// Throws dlslam::Error when options are invalid. With fewer than 3
// observations the pose is returned unchanged and all are flagged outliers.
PoseOptimizationResult OptimizePose(const CameraIntrinsics& camera, const SE3d& initial_cam_from_world,
                                    const std::vector<PoseObservation>& observations,
                                    const PoseOptimizerOptions& options = {});

}  // namespace dlslam

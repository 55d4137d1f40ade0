#pragma once
// Closed-form rigid alignment of two point sets (Horn 1987, via SVD), in the
// exact arrangement of the TUM tools' evaluate_ate.py, so that the rotation
// agrees with theirs to rounding.

#include <Eigen/Core>

#include <span>

namespace dlslam::eval {

// gt_point ~ rotation * est_point + translation.
struct RigidAlignment {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d Apply(const Eigen::Vector3d& est_point) const {
    return rotation * est_point + translation;
  }
};

// Minimises sum_i ||R est_i + t - gt_i||^2 over rotations R (det +1) and t.
// Needs equally many points, at least one (throws dlslam::Error otherwise).
// When the centred points carry no rotation information at all (every
// estimate or every ground-truth point the same) R is the identity, which
// leaves the residuals unchanged: any R gives the same ones then.
RigidAlignment AlignHorn(std::span<const Eigen::Vector3d> est, std::span<const Eigen::Vector3d> gt);

}  // namespace dlslam::eval

#pragma once
// A camera trajectory as the TUM RGB-D benchmark writes it: per pose a
// timestamp and the camera's pose in the world (world_from_cam), translation
// tx ty tz and unit quaternion qx qy qz qw.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

#include "dlslam/geometry/se3.h"

namespace dlslam {

// Bounds of a plausible trajectory: a million kilometres, 30,000 years. The
// readers refuse values beyond them, so that the evaluation's differences and
// squares stay finite.
inline constexpr double kMaxCoordinate = 1e9;  // [m]
inline constexpr double kMaxTimestamp = 1e12;  // [s]

struct StampedPose {
  double timestamp = 0.0;                                       // [s]
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();        // [m]
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // as stored; ~unit

  StampedPose() = default;
  StampedPose(double t, const SE3d& world_from_cam)
      : timestamp(t), translation(world_from_cam.translation()),
        rotation(world_from_cam.unit_quaternion()) {}

  SE3d world_from_cam() const { return SE3d(rotation, translation); }
};

using Trajectory = std::vector<StampedPose>;

// True when every timestamp is larger than the one before.
bool HasIncreasingTimestamps(const Trajectory& trajectory);

}  // namespace dlslam

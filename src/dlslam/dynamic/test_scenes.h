#pragma once
// Hand-made geometry shared by the dynamic module's tests.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <cmath>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam::dynamic::testing {

// 640x480, f = 525, no distortion (TUM freiburg3).
inline CameraIntrinsics TestCamera() { return CameraPreset("freiburg3"); }

// cam_from_world of a camera at `centre` whose optical axis (z) points at
// `target`, x axis horizontal (world y is "down", as in the camera frame).
inline SE3d LookAt(const Eigen::Vector3d& centre, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - centre).normalized();
  Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z);
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d world_from_cam_rotation;
  world_from_cam_rotation << x, y, z;
  const SE3d world_from_cam(SO3d(world_from_cam_rotation), centre);
  return world_from_cam.Inverse();
}

// A depth image (CV_32FC1) filled with `metres`.
inline cv::Mat ConstantDepth(const CameraIntrinsics& camera, float metres) {
  return cv::Mat(camera.height, camera.width, CV_32FC1, cv::Scalar(metres));
}

// A box (x in [0, 0.3] m, |y| <= 0.2 m) at z = 1.5 m before a wall at z = 3
// m, as a camera at `centre` looking along the world's z axis sees it
// (CV_32FC1 metres).
inline cv::Mat BoxBeforeWallDepth(const CameraIntrinsics& camera, const Eigen::Vector3d& centre) {
  cv::Mat depth(camera.height, camera.width, CV_32FC1);
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const Eigen::Vector3d at_box = centre + camera.Unproject({u, v}, 1.5);
      const bool box = at_box.x() >= 0.0 && at_box.x() <= 0.3 && std::abs(at_box.y()) <= 0.2;
      depth.at<float>(v, u) = box ? 1.5f : 3.0f;
    }
  }
  return depth;
}

}  // namespace dlslam::dynamic::testing

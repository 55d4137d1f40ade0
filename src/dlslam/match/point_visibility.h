#pragma once
// Whether a camera can match a map point, and where it lands: in front of the
// camera, inside the image, within the point's scale-invariance distances
// (with ORB-SLAM's 0.8 / 1.2 slack) and within a viewing-angle limit of the
// point's mean viewing direction. Shared by every projection-based matcher.

#include <Eigen/Core>

#include <optional>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"
#include "dlslam/map/map_types.h"

namespace dlslam {

struct VisibleProjection {
  Eigen::Vector3d point_cam;  // in the camera frame [m]
  Eigen::Vector2d uv;         // pixel (undistorted) [px]
  double distance = 0.0;      // from the camera centre [m]
};

class PointVisibility {
 public:
  PointVisibility(const CameraIntrinsics& camera, const SE3d& cam_from_world, double max_view_angle_deg);

  std::optional<VisibleProjection> Project(const MapPointView& point) const;

 private:
  const CameraIntrinsics& camera_;
  SE3d cam_from_world_;
  Eigen::Vector3d centre_;
  double min_cos_;
};

}  // namespace dlslam

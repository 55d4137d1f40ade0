#include "dlslam/match/point_visibility.h"

#include <cmath>

namespace dlslam {

PointVisibility::PointVisibility(const CameraIntrinsics& camera, const SE3d& cam_from_world,
                                 double max_view_angle_deg)
    : camera_(camera),
      cam_from_world_(cam_from_world),
      centre_(cam_from_world.Inverse().translation()),
      min_cos_(std::cos(max_view_angle_deg * 3.14159265358979323846 / 180.0)) {}

std::optional<VisibleProjection> PointVisibility::Project(const MapPointView& point) const {
  const Eigen::Vector3d pc = cam_from_world_ * point.position;
  if (pc.z() <= 0) return std::nullopt;
  const Eigen::Vector2d uv = camera_.Project(pc);
  if (uv.x() < 0 || uv.y() < 0 || uv.x() >= camera_.width || uv.y() >= camera_.height) return std::nullopt;
  const Eigen::Vector3d ray = point.position - centre_;
  const double distance = ray.norm();
  if (distance < 0.8 * point.min_distance || distance > 1.2 * point.max_distance) return std::nullopt;
  if (ray.dot(point.normal) < min_cos_ * distance) return std::nullopt;
  return VisibleProjection{pc, uv, distance};
}

}  // namespace dlslam

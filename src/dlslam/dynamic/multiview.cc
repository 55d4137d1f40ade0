#include "dlslam/dynamic/multiview.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {

void MultiViewOptions::Check() const {
  DLSLAM_CHECK(max_reference_views >= 1 && max_reference_views <= 100,
               "MultiViewOptions::max_reference_views {} outside [1, 100]", max_reference_views);
  DLSLAM_CHECK(max_view_angle_deg > 0 && max_view_angle_deg <= 180,
               "MultiViewOptions::max_view_angle_deg {} outside (0, 180]", max_view_angle_deg);
  DLSLAM_CHECK(depth_threshold_m > 0 && depth_threshold_m <= 10,
               "MultiViewOptions::depth_threshold_m {} outside (0, 10]", depth_threshold_m);
  DLSLAM_CHECK(depth_threshold_per_m2 >= 0 && depth_threshold_per_m2 <= 1,
               "MultiViewOptions::depth_threshold_per_m2 {} outside [0, 1]",
               depth_threshold_per_m2);
  DLSLAM_CHECK(agreement_radius_px >= 0 && agreement_radius_px <= 20,
               "MultiViewOptions::agreement_radius_px {} outside [0, 20]", agreement_radius_px);
  DLSLAM_CHECK(depth_patch_radius_px >= 0 && depth_patch_radius_px <= 20,
               "MultiViewOptions::depth_patch_radius_px {} outside [0, 20]",
               depth_patch_radius_px);
  DLSLAM_CHECK(parallax_clearance_px >= 0 && parallax_clearance_px <= 20,
               "MultiViewOptions::parallax_clearance_px {} outside [0, 20]", parallax_clearance_px);
  DLSLAM_CHECK(min_depth_m > 0 && min_depth_m < max_depth_m,
               "MultiViewOptions: need 0 < min_depth_m {} < max_depth_m {}", min_depth_m,
               max_depth_m);
}

const char* ToString(PointLabel label) {
  switch (label) {
    case PointLabel::kUntested: return "untested";
    case PointLabel::kUnknown: return "unknown";
    case PointLabel::kUnreliable: return "unreliable";
    case PointLabel::kStatic: return "static";
    case PointLabel::kDynamic: return "dynamic";
    case PointLabel::kVanished: return "vanished";
    case PointLabel::kOccluded: return "occluded";
  }
  return "?";
}

namespace {

// The (distorted) image position of a point in the camera frame, z > 0.
Eigen::Vector2d ImagePosition(const CameraIntrinsics& intrinsics, const Eigen::Vector3d& p_cam) {
  const Eigen::Vector2d normalised(p_cam.x() / p_cam.z(), p_cam.y() / p_cam.z());
  const Eigen::Vector2d n = intrinsics.HasDistortion() ? intrinsics.Distort(normalised) : normalised;
  return {intrinsics.fx * n.x() + intrinsics.cx, intrinsics.fy * n.y() + intrinsics.cy};
}

}  // namespace

void ProjectReferencePoints(const std::vector<ReferenceView>& references,
                            const SE3d& cam_from_world, const CameraIntrinsics& intrinsics,
                            std::vector<ProjectedPoint>& out, std::size_t max_views) {
  out.clear();
  const Eigen::Vector3d current_centre = cam_from_world.Inverse().translation();
  const double max_u = intrinsics.width - 0.5;
  const double max_v = intrinsics.height - 0.5;
  constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
  for (std::size_t v = 0; v < std::min(references.size(), max_views); ++v) {
    const ReferenceView& view = references[v];
    const Eigen::Vector3d reference_centre = view.cam_from_world.Inverse().translation();
    for (std::size_t p = 0; p < view.points.size(); ++p) {
      const Eigen::Vector3d& x_world = view.points[p].position_world;
      const Eigen::Vector3d x_cam = cam_from_world * x_world;
      if (!(x_cam.z() > 1e-6)) continue;
      const Eigen::Vector2d image = ImagePosition(intrinsics, x_cam);
      const double u = image.x();
      const double w = image.y();
      // Pixel centres are integers: the image covers [-0.5, size - 0.5).
      if (!(u >= -0.5 && u < max_u && w >= -0.5 && w < max_v)) continue;
      const Eigen::Vector3d ray_current = x_world - current_centre;
      const Eigen::Vector3d ray_reference = x_world - reference_centre;
      const double denominator = ray_current.norm() * ray_reference.norm();
      const double cosine =
          denominator > 0 ? std::clamp(ray_current.dot(ray_reference) / denominator, -1.0, 1.0)
                          : 1.0;
      ProjectedPoint& out_point = out.emplace_back();
      out_point.pixel = Eigen::Vector2f(static_cast<float>(u), static_cast<float>(w));
      out_point.projected_depth = static_cast<float>(x_cam.z());
      out_point.view_angle_deg = static_cast<float>(std::acos(cosine) * kRadToDeg);
      out_point.view = static_cast<int>(v);
      out_point.point = static_cast<int>(p);
    }
  }
}

std::vector<ProjectedPoint> ProjectReferencePoints(const std::vector<ReferenceView>& references,
                                                   const SE3d& cam_from_world,
                                                   const CameraIntrinsics& intrinsics) {
  std::vector<ProjectedPoint> out;
  ProjectReferencePoints(references, cam_from_world, intrinsics, out);
  return out;
}

float NearestValidDepth(const cv::Mat& depth, const Eigen::Vector2f& pixel, int radius_px,
                        float min_depth_m, float max_depth_m, cv::Point* where) {
  const int u0 = static_cast<int>(std::lround(pixel.x()));
  const int v0 = static_cast<int>(std::lround(pixel.y()));
  // Ring r holds distances in [r, r * sqrt(2)], so for radii <= 2 the first
  // ring with a valid pixel holds the nearest one (beyond, nearly so).
  for (int r = 0; r <= radius_px; ++r) {
    float best = 0.0f;
    cv::Point best_pixel;
    int best_distance2 = std::numeric_limits<int>::max();
    for (int dv = -r; dv <= r; ++dv) {
      const int v = v0 + dv;
      if (v < 0 || v >= depth.rows) continue;
      const float* row = depth.ptr<float>(v);
      const bool edge_row = dv == -r || dv == r;
      for (int du = -r; du <= r; du += edge_row ? 1 : 2 * r) {
        const int u = u0 + du;
        if (u >= 0 && u < depth.cols) {
          const float d = row[u];
          const int distance2 = du * du + dv * dv;
          // NaN fails both comparisons.
          if (d >= min_depth_m && d <= max_depth_m && distance2 < best_distance2) {
            best = d;
            best_pixel = cv::Point(u, v);
            best_distance2 = distance2;
          }
        }
        if (r == 0) break;
      }
    }
    if (best > 0.0f) {
      if (where != nullptr) *where = best_pixel;
      return best;
    }
  }
  return 0.0f;
}

namespace {

// Is the projected depth `z` measured within options.agreement_radius_px of
// `pixel`? Near a depth edge a static point projected a pixel or two off
// (pose error, the sensor's colour-depth registration, parallax at the
// silhouette) reads the other side of the edge; its own surface is next to it.
bool AgreeingDepthNearby(const cv::Mat& depth, const Eigen::Vector2f& pixel, double z, double threshold,
                         const MultiViewOptions& options, cv::Point* where) {
  const int r = options.agreement_radius_px;
  if (r <= 0) return false;
  const int u0 = static_cast<int>(std::lround(pixel.x()));
  const int v0 = static_cast<int>(std::lround(pixel.y()));
  for (int v = std::max(0, v0 - r); v <= std::min(depth.rows - 1, v0 + r); ++v) {
    const float* row = depth.ptr<float>(v);
    for (int u = std::max(0, u0 - r); u <= std::min(depth.cols - 1, u0 + r); ++u) {
      const float d = row[u];
      if (!(d >= options.min_depth_m && d <= options.max_depth_m)) continue;  // NaN fails too
      if (std::abs(z - d) <= threshold) {
        if (where != nullptr) *where = cv::Point(u, v);
        return true;
      }
    }
  }
  return false;
}

}  // namespace

PointLabel ClassifyPoint(const ProjectedPoint& point, const cv::Mat& depth,
                         const MultiViewOptions& options, cv::Point* depth_pixel) {
  const double z = point.projected_depth;
  if (!(z >= options.min_depth_m && z <= options.max_depth_m)) return PointLabel::kUnknown;
  if (point.view_angle_deg > options.max_view_angle_deg) return PointLabel::kUnreliable;
  const float measured =
      NearestValidDepth(depth, point.pixel, options.depth_patch_radius_px,
                        static_cast<float>(options.min_depth_m),
                        static_cast<float>(options.max_depth_m), depth_pixel);
  if (measured <= 0.0f) return PointLabel::kUnknown;
  const double difference = z - measured;  // > 0: something in front
  const double threshold = options.DepthThreshold(z);
  if (std::abs(difference) <= threshold) return PointLabel::kStatic;
  if (AgreeingDepthNearby(depth, point.pixel, z, threshold, options, depth_pixel)) return PointLabel::kStatic;
  return difference > 0 ? PointLabel::kDynamic : PointLabel::kVanished;
}

bool OcclusionProvesMotion(const Eigen::Vector3d& point_world, const SE3d& reference_cam_from_world,
                           const SE3d& cam_from_world, double measured_depth, const cv::Mat& depth,
                           const CameraIntrinsics& intrinsics, const MultiViewOptions& options) {
  if (!options.parallax_occlusion_check || !(measured_depth > 0)) return true;
  // The reference camera's ray to the point, in the current camera frame:
  // origin + t * direction, t in (0, 1).
  const Eigen::Vector3d origin = cam_from_world * reference_cam_from_world.Inverse().translation();
  const Eigen::Vector3d direction = cam_from_world * point_world - origin;
  if (std::abs(direction.z()) < 1e-9) return true;
  const double threshold = options.DepthThreshold(measured_depth);
  int free = 0;
  for (const double z : {measured_depth - threshold, measured_depth, measured_depth + threshold}) {
    const double t = (z - origin.z()) / direction.z();
    if (!(t > 0.0 && t < 1.0) || !(z > 1e-6)) continue;  // the ray is not at this depth between them
    const Eigen::Vector2d image = ImagePosition(intrinsics, origin + t * direction);
    const int u = static_cast<int>(std::lround(image.x()));
    const int v = static_cast<int>(std::lround(image.y()));
    const int r = options.parallax_clearance_px;
    bool read = false;
    for (int y = std::max(0, v - r); y <= std::min(depth.rows - 1, v + r); ++y) {
      const float* row = depth.ptr<float>(y);
      for (int x = std::max(0, u - r); x <= std::min(depth.cols - 1, u + r); ++x) {
        const float d = row[x];
        if (!(d >= options.min_depth_m && d <= options.max_depth_m)) continue;  // a hole: unread
        if (d <= z + threshold) return true;  // a surface on the ray, or something nearer hiding it
        read = true;
      }
    }
    free += read;
  }
  return free == 0;
}

}  // namespace dlslam::dynamic

#pragma once
// The RGB-D camera: pinhole intrinsics, Brown-Conrady distortion (k1 k2 p1 p2
// k3, OpenCV's order) and the depth scale. Units: pixels and metres.

#include <Eigen/Core>

#include <string>
#include <vector>

namespace dlslam {

// Ranges that CameraIntrinsics::Check() accepts: wide enough for any RGB-D
// camera, narrow enough that a typo or an overflowed number is refused.
inline constexpr int kMaxImageSide = 20000;             // [px]
inline constexpr double kMinFocal = 1.0, kMaxFocal = 1e6;  // [px]
inline constexpr double kMaxTangential = 0.1;           // |p1|, |p2|
inline constexpr double kMaxBf = 1e5;                   // [px m]
// Raw depth per metre: 1 for float metres, 1000 for millimetres, 5000 for TUM;
// 1e-300 or 1e300 (a typo, an overflow) would give inf or zero depth.
inline constexpr double kMinDepthFactor = 1e-2, kMaxDepthFactor = 1e5;
inline bool IsPlausibleDepthFactor(double f) { return f >= kMinDepthFactor && f <= kMaxDepthFactor; }

struct CameraIntrinsics {
  std::string name;  // e.g. "freiburg3", "bonn", "settings:my_cam.yaml"
  int width = 640;   // image size [px]
  int height = 480;
  double fx = 525.0;  // focal lengths [px]
  double fy = 525.0;
  double cx = 319.5;  // principal point [px]
  double cy = 239.5;
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;  // distortion (OpenCV order)
  // Raw depth value per metre: 5000 for TUM and Bonn PNGs, 1000 for millimetres.
  double depth_factor = 5000.0;
  // Stereo baseline times fx [px * m] for the virtual right image of RGB-D
  // tracking (ORB-SLAM's Camera.bf; 40 in its TUM settings).
  double bf = 40.0;

  bool HasDistortion() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }

  // Pixel of a point in the camera frame (z > 0), without distortion.
  Eigen::Vector2d Project(const Eigen::Vector3d& p_cam) const {
    return {fx * p_cam.x() / p_cam.z() + cx, fy * p_cam.y() / p_cam.z() + cy};
  }
  // Point in the camera frame seen at undistorted pixel uv with depth z [m].
  Eigen::Vector3d Unproject(const Eigen::Vector2d& uv, double z) const {
    return {(uv.x() - cx) / fx * z, (uv.y() - cy) / fy * z, z};
  }
  // Applies the distortion model to a normalised image point (x/z, y/z).
  // Inline: the free-space check and the multi-view check call it for every
  // cell of every view, ~60k times a frame.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xn) const {
    const double x = xn.x(), y = xn.y();
    const double r2 = x * x + y * y;
    const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x), y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
  }

  // Throws dlslam::Error naming the offending value: sizes, focal lengths and
  // depth factor outside the ranges above, a principal point outside the
  // image, or a distortion that is not a lens (not monotonic out to the image
  // corners, or scaling a radius more than 4x).
  void Check() const;
};

// The undistorted normalised ray (x/z, y/z) of every pixel centre of the
// camera's (distorted) image, row-major: what a depth pixel (u, v) with depth
// z unprojects to, times z. Computed with OpenCV's iterative undistortion.
std::vector<Eigen::Vector2f> PixelRays(const CameraIntrinsics& camera);

// Published intrinsics of the TUM RGB-D cameras (vision.in.tum.de, "Intrinsic
// Camera Calibration of the Kinect"). freiburg3 images are already undistorted.
// `name`: "freiburg1", "freiburg2", "freiburg3" (or "fr1".."fr3"), "bonn".
// Throws dlslam::Error for an unknown name.
CameraIntrinsics CameraPreset(const std::string& name);

}  // namespace dlslam

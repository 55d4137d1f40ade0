#include "dlslam/data/camera.h"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam {

namespace {

// Why the radial distortion is not a lens: it must grow monotonically from the
// centre to the farthest image corner and scale no radius by more than
// kMaxRadialScale either way (k1 = 1e10 squeezes the whole image into a
// fraction of a degree, and undistortion then returns garbage).
std::string RadialDistortionProblem(const CameraIntrinsics& c) {
  constexpr double kMaxRadialScale = 4.0;
  double corner = 0;  // normalised radius of the farthest corner (distorted)
  for (const double u : {0.0, double(c.width)}) {
    for (const double v : {0.0, double(c.height)}) {
      corner = std::max(corner, std::hypot((u - c.cx) / c.fx, (v - c.cy) / c.fy));
    }
  }
  const auto radius = [&](double r) {
    const double r2 = r * r;
    return r * (1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3)));
  };
  const double step = corner / 200;
  double previous = 0;
  for (double r = step; r <= kMaxRadialScale * corner; r += step) {
    const double distorted = radius(r);
    if (!(distorted > previous)) {
      return fmt::format("folds back at normalised radius {:.3g} (not monotonic inside the image)", r);
    }
    const double scale = distorted / r;
    if (!(scale <= kMaxRadialScale && scale >= 1 / kMaxRadialScale)) {
      return fmt::format("scales radius {:.3g} by {:.3g} (a lens stays within {}x)", r, scale,
                         kMaxRadialScale);
    }
    if (distorted >= corner) return {};
    previous = distorted;
  }
  return "never reaches the image corner";
}

}  // namespace

void CameraIntrinsics::Check() const {
  // Plain messages, not internal checks: a bad camera usually comes from a
  // user's file, and the caller adds which one.
  const auto fail = [&](const std::string& what) {
    throw Error(fmt::format("camera '{}': {}", name, what));
  };
  if (!(width > 0 && width <= kMaxImageSide && height > 0 && height <= kMaxImageSide)) {
    fail(fmt::format("image size {}x{} outside 1..{}", width, height, kMaxImageSide));
  }
  if (!(fx >= kMinFocal && fx <= kMaxFocal && fy >= kMinFocal && fy <= kMaxFocal)) {
    fail(fmt::format("focal lengths fx {} fy {} outside [{}, {}] px", fx, fy, kMinFocal, kMaxFocal));
  }
  if (!(cx >= 0 && cx < width)) fail(fmt::format("cx {} outside [0, {})", cx, width));
  if (!(cy >= 0 && cy < height)) fail(fmt::format("cy {} outside [0, {})", cy, height));
  if (!IsPlausibleDepthFactor(depth_factor)) {
    fail(fmt::format("depth factor {} outside [{}, {}] raw units per metre", depth_factor,
                     kMinDepthFactor, kMaxDepthFactor));
  }
  if (!(bf > 0 && bf <= kMaxBf)) fail(fmt::format("bf {} outside (0, {}] px m", bf, kMaxBf));
  for (const double k : {k1, k2, p1, p2, k3}) {
    if (!std::isfinite(k)) fail("distortion coefficient is not finite");
  }
  if (!(std::abs(p1) <= kMaxTangential && std::abs(p2) <= kMaxTangential)) {
    fail(fmt::format("tangential distortion p1 {} p2 {} beyond +-{}", p1, p2, kMaxTangential));
  }
  if (k1 != 0 || k2 != 0 || k3 != 0) {
    if (const std::string problem = RadialDistortionProblem(*this); !problem.empty()) {
      fail(fmt::format("radial distortion k1 {} k2 {} k3 {} {}", k1, k2, k3, problem));
    }
  }
}

CameraIntrinsics CameraPreset(const std::string& name) {
  CameraIntrinsics c;
  c.width = 640;
  c.height = 480;
  c.depth_factor = 5000.0;
  if (name == "freiburg1" || name == "fr1") {
    c.name = "freiburg1";
    c.fx = 517.306408; c.fy = 516.469215; c.cx = 318.643040; c.cy = 255.313989;
    c.k1 = 0.262383; c.k2 = -0.953104; c.p1 = -0.005358; c.p2 = 0.002628; c.k3 = 1.163314;
  } else if (name == "freiburg2" || name == "fr2") {
    c.name = "freiburg2";
    c.fx = 520.908620; c.fy = 521.007327; c.cx = 325.141442; c.cy = 249.701764;
    c.k1 = 0.231222; c.k2 = -0.784899; c.p1 = -0.003257; c.p2 = -0.000105; c.k3 = 0.917205;
  } else if (name == "freiburg3" || name == "fr3") {
    c.name = "freiburg3";
    c.fx = 535.4; c.fy = 539.2; c.cx = 320.1; c.cy = 247.6;
  } else if (name == "bonn") {
    // Bonn RGB-D Dynamic dataset (PRBonn), intrinsics and distortion d0..d4
    // (OpenCV order) from its web page; its depth PNGs use the TUM factor 5000.
    // Unlike freiburg3 its colour images are not undistorted.
    c.name = "bonn";
    c.fx = 542.822841; c.fy = 542.576870; c.cx = 315.593520; c.cy = 237.756098;
    c.k1 = 0.039903; c.k2 = -0.099343; c.p1 = -0.000730; c.p2 = -0.000144; c.k3 = 0.0;
  } else {
    throw Error("unknown camera preset '" + name +
                "' (known: freiburg1, freiburg2, freiburg3, fr1, fr2, fr3, bonn)");
  }
  return c;
}

std::vector<Eigen::Vector2f> PixelRays(const CameraIntrinsics& camera) {
  camera.Check();
  const int n = camera.width * camera.height;
  std::vector<Eigen::Vector2f> rays(static_cast<std::size_t>(n));
  if (!camera.HasDistortion()) {
    for (int v = 0; v < camera.height; ++v) {
      for (int u = 0; u < camera.width; ++u) {
        rays[static_cast<std::size_t>(v * camera.width + u)] = Eigen::Vector2f(
            static_cast<float>((u - camera.cx) / camera.fx), static_cast<float>((v - camera.cy) / camera.fy));
      }
    }
    return rays;
  }
  cv::Mat pixels(n, 1, CV_64FC2);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) pixels.at<cv::Vec2d>(v * camera.width + u) = cv::Vec2d(u, v);
  }
  const cv::Matx33d k(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const cv::Vec<double, 5> distortion(camera.k1, camera.k2, camera.p1, camera.p2, camera.k3);
  cv::Mat normalised;
  cv::undistortPoints(pixels, normalised, k, distortion);
  for (int i = 0; i < n; ++i) {
    const cv::Vec2d x = normalised.at<cv::Vec2d>(i);
    rays[static_cast<std::size_t>(i)] = Eigen::Vector2f(static_cast<float>(x[0]), static_cast<float>(x[1]));
  }
  return rays;
}

}  // namespace dlslam

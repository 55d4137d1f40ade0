#include "dlslam/data/camera.h"

#include "dlslam/util/check.h"

namespace dlslam {

Eigen::Vector2d CameraIntrinsics::Distort(const Eigen::Vector2d& xn) const {
  const double x = xn.x(), y = xn.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
          y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

void CameraIntrinsics::Check() const {
  DLSLAM_CHECK_GT(width, 0, "camera '{}'", name);
  DLSLAM_CHECK_GT(height, 0, "camera '{}'", name);
  DLSLAM_CHECK_GT(fx, 0.0, "camera '{}'", name);
  DLSLAM_CHECK_GT(fy, 0.0, "camera '{}'", name);
  DLSLAM_CHECK(cx >= 0 && cx < width, "camera '{}': cx {} outside [0, {})", name, cx, width);
  DLSLAM_CHECK(cy >= 0 && cy < height, "camera '{}': cy {} outside [0, {})", name, cy, height);
  DLSLAM_CHECK_GT(depth_factor, 0.0, "camera '{}'", name);
  DLSLAM_CHECK_GT(bf, 0.0, "camera '{}'", name);
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

}  // namespace dlslam

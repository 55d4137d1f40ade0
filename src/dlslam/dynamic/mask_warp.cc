#include "dlslam/dynamic/mask_warp.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {

void MaskWarpOptions::Check() const {
  DLSLAM_CHECK(sample_step_px >= 1, "mask warp: sample_step_px must be >= 1, got {}", sample_step_px);
  DLSLAM_CHECK(close_px >= 0, "mask warp: close_px must be >= 0, got {}", close_px);
}

MaskWarper::MaskWarper(const CameraIntrinsics& camera, const MaskWarpOptions& options)
    : camera_(camera), options_(options), rays_(PixelRays(camera)) {
  options_.Check();
}

cv::Mat MaskWarper::Warp(const cv::Mat& mask_s, const cv::Mat& depth_s, const SE3d& t_from_s, int grow_px) const {
  const int w = camera_.width, h = camera_.height;
  if (mask_s.type() != CV_8UC1 || mask_s.cols != w || mask_s.rows != h) {
    throw Error(fmt::format("mask warp: mask must be CV_8UC1 {}x{}, got type {} {}x{}", w, h, mask_s.type(),
                            mask_s.cols, mask_s.rows));
  }
  const bool has_depth = !depth_s.empty();
  if (has_depth && (depth_s.type() != CV_32FC1 || depth_s.cols != w || depth_s.rows != h)) {
    throw Error(fmt::format("mask warp: depth must be CV_32FC1 {}x{}", w, h));
  }
  const int step = options_.sample_step_px;

  // The median depth of the masked pixels stands in where a pixel has none
  // (hair, dark clothes, the person's outline on a structured-light sensor).
  std::vector<float> depths;
  if (has_depth) {
    for (int v = 0; v < h; v += step) {
      const auto* m = mask_s.ptr<std::uint8_t>(v);
      const auto* d = depth_s.ptr<float>(v);
      for (int u = 0; u < w; u += step) {
        if (m[u] && d[u] > 0 && std::isfinite(d[u])) depths.push_back(d[u]);
      }
    }
  }
  float fallback = 0;
  if (!depths.empty()) {
    std::nth_element(depths.begin(), depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2), depths.end());
    fallback = depths[depths.size() / 2];
  }

  cv::Mat warped = cv::Mat::zeros(h, w, CV_8UC1);
  // A square of side 2 * splat + 1 around (u, v), clipped to the image.
  const auto mark = [&](int u, int v, int splat) {
    for (int y = std::max(0, v - splat); y <= std::min(h - 1, v + splat); ++y) {
      std::uint8_t* row = warped.ptr<std::uint8_t>(y);
      for (int x = std::max(0, u - splat); x <= std::min(w - 1, u + splat); ++x) row[x] = 255;
    }
  };
  const Eigen::Matrix3d rotation = t_from_s.rotationMatrix();
  const Eigen::Vector3d translation = t_from_s.translation();
  const int splat = std::max(1, step / 2);
  for (int v = 0; v < h; v += step) {
    const auto* m = mask_s.ptr<std::uint8_t>(v);
    const float* d = has_depth ? depth_s.ptr<float>(v) : nullptr;
    for (int u = 0; u < w; u += step) {
      if (!m[u]) continue;
      float z = d && d[u] > 0 && std::isfinite(d[u]) ? d[u] : fallback;
      if (z <= 0) {  // no depth anywhere in the mask: the pixel stays where it was
        mark(u, v, splat);
        continue;
      }
      const Eigen::Vector2f& ray = rays_[static_cast<std::size_t>(v * w + u)];
      const Eigen::Vector3d p = rotation * Eigen::Vector3d(ray.x() * z, ray.y() * z, z) + translation;
      if (p.z() <= 1e-3) continue;  // behind the camera now
      const Eigen::Vector2d xn(p.x() / p.z(), p.y() / p.z());
      const Eigen::Vector2d xd = camera_.Distort(xn);
      const double ut = camera_.fx * xd.x() + camera_.cx, vt = camera_.fy * xd.y() + camera_.cy;
      if (!(ut > -splat && ut < w + splat && vt > -splat && vt < h + splat)) continue;
      const int ui = static_cast<int>(std::lround(ut)), vi = static_cast<int>(std::lround(vt));
      mark(ui, vi, splat);
    }
  }
  if (options_.close_px > 0) {
    const int k = 2 * options_.close_px + 1;
    cv::morphologyEx(warped, warped, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));  // separable: fast
  }
  if (grow_px > 0) {
    const int k = 2 * grow_px + 1;
    cv::dilate(warped, warped, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  }
  return warped;
}

}  // namespace dlslam::dynamic

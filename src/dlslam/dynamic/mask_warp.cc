#include "dlslam/dynamic/mask_warp.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "dlslam/dynamic/cell_grid.h"
#include "dlslam/image/disc_dilation.h"
#include "dlslam/image/upsample.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic {

void MaskWarpOptions::Check() const {
  DLSLAM_CHECK(cell_px >= 1 && cell_px <= 64, "mask warp: cell_px must be in [1, 64], got {}", cell_px);
  DLSLAM_CHECK(close_px >= 0, "mask warp: close_px must be >= 0, got {}", close_px);
}

namespace {

// Radius r [px] in whole cells, rounded up: the carried mask never shrinks.
int InCells(int r, int cell) { return (r + cell - 1) / cell; }

}  // namespace

MaskWarper::MaskWarper(const CameraIntrinsics& camera, const MaskWarpOptions& options)
    : camera_(camera), options_(options) {
  options_.Check();
  cells_ = CellGridSize(camera.width, camera.height, options_.cell_px);
  rays_ = CellCentreRays(camera, options_.cell_px);
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
  const int cell = options_.cell_px;
  // A cell is masked when any of its pixels is (the area average is > 0).
  cv::Mat touched = mask_s;
  if (cell > 1) {
    cv::Mat binary = mask_s != 0;
    cv::copyMakeBorder(binary, binary, 0, cells_.height * cell - h, 0, cells_.width * cell - w, cv::BORDER_CONSTANT, 0);
    cv::resize(binary, touched, cells_, 0, 0, cv::INTER_AREA);
  }
  const auto depth_at = [&](int cx, int cy) {
    const cv::Point p = CellCentre(cx, cy, cell, w, h);
    const float d = depth_s.at<float>(p.y, p.x);
    return d > 0 && std::isfinite(d) ? d : 0.0f;
  };

  // The median depth of the masked cells stands in where a cell has none
  // (hair, dark clothes, the person's outline on a structured-light sensor).
  std::vector<float> depths;
  if (has_depth) {
    for (int cy = 0; cy < cells_.height; ++cy) {
      const auto* m = touched.ptr<std::uint8_t>(cy);
      for (int cx = 0; cx < cells_.width; ++cx) {
        if (!m[cx]) continue;
        if (const float d = depth_at(cx, cy); d > 0) depths.push_back(d);
      }
    }
  }
  float fallback = 0;
  if (!depths.empty()) {
    std::nth_element(depths.begin(), depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2), depths.end());
    fallback = depths[depths.size() / 2];
  }

  cv::Mat carried = cv::Mat::zeros(cells_, CV_8UC1);
  const Eigen::Matrix3d rotation = t_from_s.rotationMatrix();
  const Eigen::Vector3d translation = t_from_s.translation();
  for (int cy = 0; cy < cells_.height; ++cy) {
    const auto* m = touched.ptr<std::uint8_t>(cy);
    for (int cx = 0; cx < cells_.width; ++cx) {
      if (!m[cx]) continue;
      float z = has_depth ? depth_at(cx, cy) : 0.0f;
      if (z <= 0) z = fallback;
      if (z <= 0) {  // no depth anywhere in the mask: the cell stays where it was
        carried.at<std::uint8_t>(cy, cx) = 255;
        continue;
      }
      const Eigen::Vector2f& ray = rays_[static_cast<std::size_t>(cy * cells_.width + cx)];
      const Eigen::Vector3d p = rotation * Eigen::Vector3d(ray.x() * z, ray.y() * z, z) + translation;
      if (p.z() <= 1e-3) continue;  // behind the camera now
      const Eigen::Vector2d xd = camera_.Distort(Eigen::Vector2d(p.x() / p.z(), p.y() / p.z()));
      const double ut = camera_.fx * xd.x() + camera_.cx, vt = camera_.fy * xd.y() + camera_.cy;
      if (!(ut >= 0 && ut < w && vt >= 0 && vt < h)) continue;  // out of view now
      carried.at<std::uint8_t>(static_cast<int>(vt) / cell, static_cast<int>(ut) / cell) = 255;
    }
  }
  if (const int close = InCells(options_.close_px, cell); close > 0) {
    const int k = 2 * close + 1;
    cv::morphologyEx(carried, carried, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));
  }
  if (const int grow = InCells(grow_px, cell); grow > 0) {
    image::DilateDisc(carried, grow, carried);
  }
  if (cell == 1) return carried;
  return image::UpsampleNearest(carried, cell, {w, h});
}

}  // namespace dlslam::dynamic

#include "dlslam/dynamic/free_space.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "dlslam/dynamic/cell_grid.h"
#include "dlslam/image/connected_components.h"
#include "dlslam/image/upsample.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic {

void FreeSpaceOptions::Check() const {
  DLSLAM_CHECK(cell_px >= 1 && cell_px <= 32, "free space: cell_px must be in [1, 32], got {}", cell_px);
  DLSLAM_CHECK(view_every_frames >= 1, "free space: view_every_frames must be >= 1, got {}", view_every_frames);
  DLSLAM_CHECK(max_views >= 1, "free space: max_views must be >= 1, got {}", max_views);
  DLSLAM_CHECK(neighbourhood_cells >= 0 && neighbourhood_cells <= 16,
               "free space: neighbourhood_cells must be in [0, 16], got {}", neighbourhood_cells);
  DLSLAM_CHECK(depth_threshold_m >= 0 && depth_threshold_per_m2 >= 0,
               "free space: the depth thresholds must be >= 0, got {} m and {} 1/m", depth_threshold_m,
               depth_threshold_per_m2);
  DLSLAM_CHECK(min_region_cells >= 1, "free space: min_region_cells must be >= 1, got {}", min_region_cells);
  DLSLAM_CHECK(max_violated_share > 0 && max_violated_share <= 1,
               "free space: max_violated_share must be in (0, 1], got {}", max_violated_share);
  DLSLAM_CHECK(min_depth_m > 0 && max_depth_m > min_depth_m,
               "free space: need 0 < min_depth_m < max_depth_m, got {} and {}", min_depth_m, max_depth_m);
}

FreeSpaceCheck::FreeSpaceCheck(const CameraIntrinsics& camera, const FreeSpaceOptions& options)
    : camera_(camera), options_(options) {
  options_.Check();
  cells_ = CellGridSize(camera.width, camera.height, options_.cell_px);
  rays_ = CellCentreRays(camera, options_.cell_px);
}

void FreeSpaceCheck::CheckDepth(const cv::Mat& depth) const {
  DLSLAM_CHECK(depth.type() == CV_32FC1 && depth.cols == camera_.width && depth.rows == camera_.height,
               "free space: depth must be CV_32FC1 {}x{}, got type {} {}x{}", camera_.width, camera_.height,
               depth.type(), depth.cols, depth.rows);
}

void FreeSpaceCheck::Reset() {
  views_.clear();
  offered_ = 0;
}

void FreeSpaceCheck::Offer(const cv::Mat& depth, const SE3d& cam_from_world) {
  CheckDepth(depth);
  if (offered_++ % options_.view_every_frames != 0) return;
  const int cell = options_.cell_px;
  const auto valid = [this](float d) {
    return std::isfinite(d) && d >= options_.min_depth_m && d <= options_.max_depth_m;
  };
  // The nearest depth of each cell; a cell mostly without depth is unknown
  // (0), and so is every neighbourhood that holds it: a hole may hide a
  // nearer surface.
  cv::Mat nearest(cells_, CV_32FC1, cv::Scalar(0));
  for (int cy = 0; cy < cells_.height; ++cy) {
    for (int cx = 0; cx < cells_.width; ++cx) {
      float best = INFINITY;
      int seen = 0, total = 0;
      for (int v = cy * cell; v < std::min(camera_.height, (cy + 1) * cell); ++v) {
        const float* row = depth.ptr<float>(v);
        for (int u = cx * cell; u < std::min(camera_.width, (cx + 1) * cell); ++u) {
          ++total;
          if (!valid(row[u])) continue;
          ++seen;
          best = std::min(best, row[u]);
        }
      }
      if (2 * seen >= total && seen > 0) nearest.at<float>(cy, cx) = best;
    }
  }
  if (const int n = options_.neighbourhood_cells; n > 0) {
    cv::erode(nearest, nearest, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * n + 1, 2 * n + 1)),
              cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  }
  views_.push_back({cam_from_world, nearest});
  while (views_.size() > static_cast<std::size_t>(options_.max_views)) views_.pop_front();
}

cv::Mat FreeSpaceCheck::CentreDepths(const cv::Mat& depth) const {
  cv::Mat centre(cells_, CV_32FC1, cv::Scalar(0));
  const int cell = options_.cell_px;
  for (int cy = 0; cy < cells_.height; ++cy) {
    for (int cx = 0; cx < cells_.width; ++cx) {
      const cv::Point p = CellCentre(cx, cy, cell, camera_.width, camera_.height);
      const float d = depth.at<float>(p.y, p.x);
      if (std::isfinite(d) && d >= options_.min_depth_m && d <= options_.max_depth_m) centre.at<float>(cy, cx) = d;
    }
  }
  return centre;
}

cv::Mat FreeSpaceCheck::Violations(const cv::Mat& depth, const SE3d& cam_from_world, FreeSpaceStats* stats) const {
  CheckDepth(depth);
  FreeSpaceStats local;
  FreeSpaceStats& s = stats != nullptr ? *stats : local;
  s = FreeSpaceStats{};
  s.views = views();
  if (views_.empty()) return {};
  // The current cells' points, once for all views, one array per axis so
  // that the projection below runs on vector registers.
  const cv::Mat centre = CentreDepths(depth);
  std::vector<float> px, py, pz;
  std::vector<int> cell_of;
  for (std::vector<float>* axis : {&px, &py, &pz}) axis->reserve(static_cast<std::size_t>(cells_.area()));
  cell_of.reserve(static_cast<std::size_t>(cells_.area()));
  for (int i = 0; i < cells_.area(); ++i) {
    const float z = centre.ptr<float>()[i];
    if (z <= 0) continue;
    const Eigen::Vector2f& ray = rays_[static_cast<std::size_t>(i)];
    px.push_back(ray.x() * z);
    py.push_back(ray.y() * z);
    pz.push_back(z);
    cell_of.push_back(i);
  }
  const std::size_t n_points = px.size();
  const int cell = options_.cell_px;
  const bool distorted = camera_.HasDistortion();
  const float fx = static_cast<float>(camera_.fx), fy = static_cast<float>(camera_.fy);
  const float cx = static_cast<float>(camera_.cx), cy = static_cast<float>(camera_.cy);
  const float min_depth = static_cast<float>(options_.min_depth_m);
  const float width = static_cast<float>(camera_.width), height = static_cast<float>(camera_.height);
  const float a = static_cast<float>(options_.depth_threshold_m), b = static_cast<float>(options_.depth_threshold_per_m2);
  cv::Mat violated(cells_, CV_8UC1, cv::Scalar(0));
  std::vector<int> through_cells;
  // Per point in a view: its depth there and its pixel, -1 when it falls
  // behind the view or outside its image.
  std::vector<float> view_z(n_points), view_u(n_points), view_v(n_points);
  const SE3d world_from_cam = cam_from_world.Inverse();
  for (const View& view : views_) {
    const SE3d view_from_cam = view.cam_from_world * world_from_cam;
    const Eigen::Matrix3f r = view_from_cam.rotationMatrix().cast<float>();
    const Eigen::Vector3f t = view_from_cam.translation().cast<float>();
    // No branches in these loops: the compiler vectorises them.
    for (std::size_t k = 0; k < n_points; ++k) {
      const float x = r(0, 0) * px[k] + r(0, 1) * py[k] + r(0, 2) * pz[k] + t.x();
      const float y = r(1, 0) * px[k] + r(1, 1) * py[k] + r(1, 2) * pz[k] + t.y();
      const float z = r(2, 0) * px[k] + r(2, 1) * py[k] + r(2, 2) * pz[k] + t.z();
      view_z[k] = z;
      view_u[k] = x;
      view_v[k] = y;
    }
    if (distorted) {
      for (std::size_t k = 0; k < n_points; ++k) {
        const Eigen::Vector2d xd = camera_.Distort(Eigen::Vector2d(view_u[k] / view_z[k], view_v[k] / view_z[k]));
        view_u[k] = static_cast<float>(camera_.fx * xd.x() + camera_.cx);
        view_v[k] = static_cast<float>(camera_.fy * xd.y() + camera_.cy);
      }
    } else {
      for (std::size_t k = 0; k < n_points; ++k) {
        view_u[k] = fx * view_u[k] / view_z[k] + cx;
        view_v[k] = fy * view_v[k] / view_z[k] + cy;
      }
    }
    through_cells.clear();
    int compared = 0;
    for (std::size_t k = 0; k < n_points; ++k) {
      const float z = view_z[k], u = view_u[k], v = view_v[k];
      if (z < min_depth) continue;
      if (!(u >= 0 && u < width && v >= 0 && v < height)) continue;
      const float seen = view.nearest.ptr<float>(static_cast<int>(v) / cell)[static_cast<int>(u) / cell];
      if (seen <= 0) continue;
      ++compared;
      if (seen - z > a + b * z * z) through_cells.push_back(cell_of[k]);
    }
    if (compared == 0) continue;
    if (static_cast<double>(through_cells.size()) > options_.max_violated_share * compared) {
      ++s.views_ignored;
      continue;
    }
    s.cells_compared += compared;
    for (const int i : through_cells) violated.ptr<std::uint8_t>()[i] = 255;
  }
  // Small blobs are depth noise or a pose a little off at an edge.
  cv::Mat labels;
  std::vector<int> areas;
  const int n = image::LabelComponents(violated, labels, &areas);
  std::vector<std::uint8_t> keep(static_cast<std::size_t>(n), 0);
  for (int i = 1; i < n; ++i) {
    keep[static_cast<std::size_t>(i)] = areas[static_cast<std::size_t>(i)] >= options_.min_region_cells;
  }
  const int* label = labels.ptr<int>();
  auto* mask = violated.ptr<std::uint8_t>();
  for (int i = 0; i < cells_.area(); ++i) {
    mask[i] = keep[static_cast<std::size_t>(label[i])] ? 255 : 0;
    s.cells_violated += mask[i] != 0;
  }
  return image::UpsampleNearest(violated, cell, {camera_.width, camera_.height});
}

}  // namespace dlslam::dynamic

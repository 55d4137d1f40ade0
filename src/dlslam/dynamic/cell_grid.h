#pragma once
// A grid of cell x cell px cells over a camera image, for the checks that
// work per cell instead of per pixel (mask_warp.h, free_space.h). The last
// row and column of cells may be partial.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <algorithm>
#include <vector>

#include "dlslam/data/camera.h"

namespace dlslam::dynamic {

// The number of cells across and down a width x height image.
inline cv::Size CellGridSize(int width, int height, int cell) {
  return {(width + cell - 1) / cell, (height + cell - 1) / cell};
}

// The pixel at the centre of cell (cx, cy), inside the image.
inline cv::Point CellCentre(int cx, int cy, int cell, int width, int height) {
  return {std::min(width - 1, cx * cell + cell / 2), std::min(height - 1, cy * cell + cell / 2)};
}

// The undistorted normalised ray (PixelRays) of every cell's centre pixel,
// row-major over the grid.
inline std::vector<Eigen::Vector2f> CellCentreRays(const CameraIntrinsics& camera, int cell) {
  const cv::Size cells = CellGridSize(camera.width, camera.height, cell);
  const std::vector<Eigen::Vector2f> pixel_rays = PixelRays(camera);
  std::vector<Eigen::Vector2f> rays;
  rays.reserve(static_cast<std::size_t>(cells.area()));
  for (int cy = 0; cy < cells.height; ++cy) {
    for (int cx = 0; cx < cells.width; ++cx) {
      const cv::Point p = CellCentre(cx, cy, cell, camera.width, camera.height);
      rays.push_back(pixel_rays[static_cast<std::size_t>(p.y * camera.width + p.x)]);
    }
  }
  return rays;
}

}  // namespace dlslam::dynamic

#include "dlslam/dynamic/mask_completion.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {

void MaskCompletionOptions::Check() const {
  DLSLAM_CHECK(reach_m >= 0 && reach_m <= 5, "MaskCompletionOptions::reach_m {} outside [0, 5]", reach_m);
  DLSLAM_CHECK(depth_margin_m >= 0 && depth_margin_m <= 5, "MaskCompletionOptions::depth_margin_m {} outside [0, 5]",
               depth_margin_m);
  DLSLAM_CHECK_GE(min_segment_pixels, 1, "MaskCompletionOptions::min_segment_pixels");
  DLSLAM_CHECK(pixel_step == 1 || pixel_step == 2, "MaskCompletionOptions::pixel_step {} must be 1 or 2", pixel_step);
  DLSLAM_CHECK(min_depth_m > 0 && min_depth_m < max_depth_m,
               "MaskCompletionOptions: valid depths [{}, {}] m must satisfy 0 < min < max", min_depth_m, max_depth_m);
}

namespace {

// What a segment admits: pixels within radius_px of it whose depth lies in
// [near_m, far_m]. An empty band (near > far) admits nothing.
struct Band {
  float radius_px = 0.0f;
  float near_m = 1.0f;
  float far_m = 0.0f;
};

float Quantile(std::vector<float>& values, double q) {
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[static_cast<std::size_t>(k)];
}

// CompleteMaskByDepth on one grid, `mask` 0 / 255: each pixel stands for
// pixel_area image pixels (for min_segment_pixels).
cv::Mat Complete(const cv::Mat& mask, const cv::Mat& depth, double focal_px, const MaskCompletionOptions& options,
                 int pixel_area) {
  cv::Mat completed = mask.clone();

  // Every pixel's distance to the nearest segment and that segment's label
  // (each connected component of the mask gets one).
  cv::Mat distance, labels;
  cv::distanceTransform(mask == 0, distance, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_CCOMP);
  double max_label = 0;
  cv::minMaxLoc(labels, nullptr, &max_label);
  const auto segments = static_cast<std::size_t>(max_label) + 1;

  const auto valid = [&options](float z) { return z >= options.min_depth_m && z <= options.max_depth_m; };
  std::vector<int> area(segments, 0);
  std::vector<std::vector<float>> depths(segments);
  for (int v = 0; v < mask.rows; ++v) {
    const auto* m = mask.ptr<std::uint8_t>(v);
    const auto* z = depth.ptr<float>(v);
    const auto* l = labels.ptr<int>(v);
    for (int u = 0; u < mask.cols; ++u) {
      if (m[u] == 0) continue;
      const auto s = static_cast<std::size_t>(l[u]);
      ++area[s];
      if (valid(z[u])) depths[s].push_back(z[u]);
    }
  }
  std::vector<Band> bands(segments);
  for (std::size_t s = 0; s < segments; ++s) {
    // Half the pixels of a segment with depth, at least: the rest is a hole
    // the sensor could not see, whose band would be a guess.
    if (area[s] * pixel_area < options.min_segment_pixels || 2 * depths[s].size() < static_cast<std::size_t>(area[s])) continue;
    const float median = Quantile(depths[s], 0.5);
    bands[s].radius_px = static_cast<float>(focal_px * options.reach_m / median);
    bands[s].near_m = Quantile(depths[s], 0.25) - static_cast<float>(options.depth_margin_m);
    bands[s].far_m = Quantile(depths[s], 0.75) + static_cast<float>(options.depth_margin_m);
  }

  for (int v = 0; v < mask.rows; ++v) {
    const auto* z = depth.ptr<float>(v);
    const auto* l = labels.ptr<int>(v);
    const auto* d = distance.ptr<float>(v);
    auto* out = completed.ptr<std::uint8_t>(v);
    for (int u = 0; u < mask.cols; ++u) {
      if (out[u] != 0 || !valid(z[u])) continue;
      const Band& band = bands[static_cast<std::size_t>(l[u])];
      if (d[u] <= band.radius_px && z[u] >= band.near_m && z[u] <= band.far_m) out[u] = 255;
    }
  }
  return completed;
}

}  // namespace

cv::Mat CompleteMaskByDepth(const cv::Mat& mask, const cv::Mat& depth, double focal_px,
                            const MaskCompletionOptions& options) {
  options.Check();
  DLSLAM_CHECK(mask.type() == CV_8UC1, "CompleteMaskByDepth: the mask must be CV_8UC1, got type {}", mask.type());
  DLSLAM_CHECK(depth.type() == CV_32FC1 && depth.size() == mask.size(),
               "CompleteMaskByDepth: the depth must be CV_32FC1 {}x{}, got type {} {}x{}", mask.cols, mask.rows,
               depth.type(), depth.cols, depth.rows);
  DLSLAM_CHECK(focal_px > 0 && std::isfinite(focal_px), "CompleteMaskByDepth: focal length {} px", focal_px);
  cv::Mat completed = (mask != 0);
  if (!options.enabled || options.reach_m == 0 || cv::countNonZero(completed) == 0) return completed;
  const int step = options.pixel_step;
  if (step == 1 || mask.cols < 2 * step || mask.rows < 2 * step) {
    return Complete(completed, depth, focal_px, options, 1);
  }
  // On a coarser grid (nearest neighbour: depths are not blended across a
  // silhouette), then back at full size; the network's own pixels stay exact.
  const cv::Size grid(mask.cols / step, mask.rows / step);
  cv::Mat small_mask, small_depth, grown;
  cv::resize(completed, small_mask, grid, 0, 0, cv::INTER_NEAREST);
  cv::resize(depth, small_depth, grid, 0, 0, cv::INTER_NEAREST);
  cv::resize(Complete(small_mask, small_depth, focal_px / step, options, step * step), grown, mask.size(), 0, 0,
             cv::INTER_NEAREST);
  return completed | grown;
}

}  // namespace dlslam::dynamic

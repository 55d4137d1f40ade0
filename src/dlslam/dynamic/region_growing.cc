#include "dlslam/dynamic/region_growing.h"

#include <cmath>
#include <cstdint>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {

void RegionGrowingOptions::Check() const {
  DLSLAM_CHECK(max_step_m >= 0 && max_step_m <= 1,
               "RegionGrowingOptions::max_step_m {} outside [0, 1]", max_step_m);
  DLSLAM_CHECK(max_step_relative >= 0 && max_step_relative <= 1,
               "RegionGrowingOptions::max_step_relative {} outside [0, 1]", max_step_relative);
  DLSLAM_CHECK(max_depth_from_seed_m > 0 && max_depth_from_seed_m <= 100,
               "RegionGrowingOptions::max_depth_from_seed_m {} outside (0, 100]",
               max_depth_from_seed_m);
  DLSLAM_CHECK(max_distance_from_seed_px >= 0,
               "RegionGrowingOptions::max_distance_from_seed_px {} < 0 (0 = no limit)",
               max_distance_from_seed_px);
  DLSLAM_CHECK(max_region_pixels >= 1, "RegionGrowingOptions::max_region_pixels {} < 1",
               max_region_pixels);
  DLSLAM_CHECK(min_depth_m > 0 && min_depth_m < max_depth_m,
               "RegionGrowingOptions: need 0 < min_depth_m {} < max_depth_m {}", min_depth_m,
               max_depth_m);
}

cv::Mat GrowDynamicRegions(const cv::Mat& depth, const std::vector<cv::Point2f>& seeds,
                           const RegionGrowingOptions& options) {
  DLSLAM_CHECK(depth.type() == CV_32FC1, "GrowDynamicRegions: depth must be CV_32FC1, got type {}",
               depth.type());
  cv::Mat mask = cv::Mat::zeros(depth.size(), CV_8UC1);
  if (seeds.empty()) return mask;
  const float min_depth = static_cast<float>(options.min_depth_m);
  const float max_depth = static_cast<float>(options.max_depth_m);
  const float step_m = static_cast<float>(options.max_step_m);
  const float step_relative = static_cast<float>(options.max_step_relative);
  const float from_seed = static_cast<float>(options.max_depth_from_seed_m);
  const double reach = options.max_distance_from_seed_px;
  const long reach2 = reach > 0 ? static_cast<long>(reach * reach) : -1;
  const int cols = depth.cols;
  const int rows = depth.rows;
  // Breadth-first, so a region cut at max_region_pixels is a compact blob
  // around its seed. Linear pixel indices; one allocation per call.
  std::vector<int> queue;
  queue.reserve(4096);
  for (const cv::Point2f& seed : seeds) {
    const int u0 = static_cast<int>(std::lround(seed.x));
    const int v0 = static_cast<int>(std::lround(seed.y));
    if (u0 < 0 || u0 >= cols || v0 < 0 || v0 >= rows) continue;
    if (mask.at<std::uint8_t>(v0, u0) != 0) continue;  // inside an earlier region
    const float seed_depth = depth.at<float>(v0, u0);
    if (!(seed_depth >= min_depth && seed_depth <= max_depth)) continue;
    int region_pixels = 1;
    mask.at<std::uint8_t>(v0, u0) = 255;
    queue.clear();
    queue.push_back(v0 * cols + u0);
    for (std::size_t head = 0;
         head < queue.size() && region_pixels < options.max_region_pixels; ++head) {
      const int index = queue[head];
      const int u = index % cols;
      const int v = index / cols;
      const float d = depth.at<float>(v, u);
      const float max_step = step_m + step_relative * d;
      const int neighbours[4][2] = {{u - 1, v}, {u + 1, v}, {u, v - 1}, {u, v + 1}};
      for (const auto& n : neighbours) {
        if (n[0] < 0 || n[0] >= cols || n[1] < 0 || n[1] >= rows) continue;
        std::uint8_t& m = mask.at<std::uint8_t>(n[1], n[0]);
        if (m != 0) continue;
        const float dn = depth.at<float>(n[1], n[0]);
        if (!(dn >= min_depth && dn <= max_depth)) continue;
        if (std::abs(dn - d) > max_step || std::abs(dn - seed_depth) > from_seed) continue;
        if (reach2 >= 0) {
          const long du = n[0] - u0, dv = n[1] - v0;
          if (du * du + dv * dv > reach2) continue;
        }
        m = 255;
        queue.push_back(n[1] * cols + n[0]);
        if (++region_pixels >= options.max_region_pixels) break;
      }
    }
  }
  return mask;
}

}  // namespace dlslam::dynamic

#include "dlslam/dynamic/region_growing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dlslam/image/upsample.h"
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
  DLSLAM_CHECK(max_distance_from_seed_m >= 0 && max_distance_from_seed_m <= 100,
               "RegionGrowingOptions::max_distance_from_seed_m {} outside [0, 100] (0 = no limit)",
               max_distance_from_seed_m);
  DLSLAM_CHECK(static_distance_from_seed_m >= 0 && static_distance_from_seed_m <= 100,
               "RegionGrowingOptions::static_distance_from_seed_m {} outside [0, 100] (0 = no "
               "limit)",
               static_distance_from_seed_m);
  DLSLAM_CHECK(static_head_start_px >= 0 && static_head_start_px <= 1000,
               "RegionGrowingOptions::static_head_start_px {} outside [0, 1000]",
               static_head_start_px);
  DLSLAM_CHECK(pixel_step == 1 || pixel_step == 2, "RegionGrowingOptions::pixel_step {} is not 1 or 2",
               pixel_step);
  DLSLAM_CHECK(max_region_pixels >= 1, "RegionGrowingOptions::max_region_pixels {} < 1",
               max_region_pixels);
  DLSLAM_CHECK(min_depth_m > 0 && min_depth_m < max_depth_m,
               "RegionGrowingOptions: need 0 < min_depth_m {} < max_depth_m {}", min_depth_m,
               max_depth_m);
}

namespace {

constexpr std::uint8_t kFree = 0;
constexpr std::uint8_t kStaticOwner = 1;
constexpr std::uint8_t kDynamicOwner = 255;
constexpr std::uint8_t kBlocked = 2;  // no valid depth, or the grid's border

}  // namespace

cv::Mat GrowDynamicRegions(const cv::Mat& depth, const CameraIntrinsics& camera,
                           const std::vector<cv::Point2f>& dynamic_seeds,
                           const std::vector<cv::Point2f>& static_seeds,
                           const RegionGrowingOptions& options, RegionGrowingBuffers* buffers) {
  DLSLAM_CHECK(depth.type() == CV_32FC1, "GrowDynamicRegions: depth must be CV_32FC1, got type {}",
               depth.type());
  DLSLAM_CHECK(depth.cols == camera.width && depth.rows == camera.height,
               "GrowDynamicRegions: depth is {}x{}, the camera {}x{}", depth.cols, depth.rows,
               camera.width, camera.height);
  if (dynamic_seeds.empty()) return cv::Mat::zeros(depth.size(), CV_8UC1);
  RegionGrowingBuffers own;
  RegionGrowingBuffers& b = buffers != nullptr ? *buffers : own;
  using Cell = RegionGrowingBuffers::Cell;
  using Seed = RegionGrowingBuffers::Seed;
  // The grid: every step-th pixel of the depth image, with a border of one
  // blocked cell on every side so that a neighbour needs no bounds check.
  const int step = options.pixel_step;
  const int cols = (depth.cols + step - 1) / step;
  const int rows = (depth.rows + step - 1) / step;
  const int stride = cols + 2;
  const auto cells = static_cast<std::size_t>(stride) * static_cast<std::size_t>(rows + 2);
  const auto at = [stride](int u, int v) { return static_cast<std::size_t>((v + 1) * stride + u + 1); };
  const float min_depth = static_cast<float>(options.min_depth_m);
  const float max_depth = static_cast<float>(options.max_depth_m);
  // Per cell its depth and 3-D point (pinhole), written for the cells with a
  // valid depth (the only ones ever read); the others and the border are
  // blocked from the start.
  b.cells.resize(cells);  // no initialisation needed: see above
  Cell* cell = b.cells.data();
  b.owner_kind.create(rows + 2, stride, CV_8UC1);
  b.owner_kind.setTo(cv::Scalar(kBlocked));
  std::uint8_t* kind_of = b.owner_kind.ptr<std::uint8_t>();
  b.ray_x.resize(static_cast<std::size_t>(cols));
  for (int u = 0; u < cols; ++u) {
    b.ray_x[static_cast<std::size_t>(u)] = static_cast<float>((u * step - camera.cx) / camera.fx);
  }
  for (int v = 0; v < rows; ++v) {
    const float* row = depth.ptr<float>(v * step);
    const auto ray_y = static_cast<float>((v * step - camera.cy) / camera.fy);
    for (int u = 0; u < cols; ++u) {
      const float z = row[u * step];
      if (!(z >= min_depth && z <= max_depth)) continue;
      const std::size_t i = at(u, v);
      cell[i].z = z;
      cell[i].x = b.ray_x[static_cast<std::size_t>(u)] * z;
      cell[i].y = ray_y * z;
      kind_of[i] = kFree;
    }
  }
  const float step_m = static_cast<float>(options.max_step_m * step);
  const float step_relative = static_cast<float>(options.max_step_relative * step);
  const float from_seed = static_cast<float>(options.max_depth_from_seed_m);
  const auto squared_or_none = [](double metres) {
    return metres > 0 ? static_cast<float>(metres * metres) : -1.0f;
  };
  const int max_pixels = std::max(1, options.max_region_pixels / (step * step));
  const float reach2[2] = {squared_or_none(options.max_distance_from_seed_m),
                           squared_or_none(options.static_distance_from_seed_m)};

  // One breadth-first fill from all seeds at once: a pixel goes to the fill
  // that reaches it in the fewest steps. Dynamic seeds are queued first, so
  // they win ties and a pixel that is both keeps its dynamic evidence.
  // A cell's seed is written when it is claimed and read only for claimed
  // cells.
  std::vector<Seed>& seeds = b.seeds;
  seeds.clear();
  std::vector<int>& queue = b.queue;
  queue.clear();
  const auto add_seeds = [&](const std::vector<cv::Point2f>& pixels, std::uint8_t kind) {
    for (const cv::Point2f& p : pixels) {
      const int u = static_cast<int>(std::lround(p.x / static_cast<float>(step)));
      const int v = static_cast<int>(std::lround(p.y / static_cast<float>(step)));
      if (u < 0 || u >= cols || v < 0 || v >= rows) continue;
      const std::size_t index = at(u, v);
      if (kind_of[index] != kFree) continue;  // an earlier seed's pixel, or no depth
      kind_of[index] = kind;
      cell[index].seed = static_cast<int>(seeds.size());
      seeds.push_back({cell[index].x, cell[index].y, cell[index].z, 1});
      queue.push_back(static_cast<int>(index));
    }
  };
  add_seeds(dynamic_seeds, kDynamicOwner);
  if (queue.empty()) return cv::Mat::zeros(depth.size(), CV_8UC1);
  // Breadth-first levels: [level_end of the previous level, level_end).
  const int head_start = (options.static_head_start_px + step - 1) / step;
  bool static_started = !options.static_points_compete;
  if (!static_started && head_start == 0) {
    add_seeds(static_seeds, kStaticOwner);
    static_started = true;
  }
  std::size_t level_end = queue.size();
  int level = 0;
  // Dynamic pixels queued and not yet expanded: once none is left, the
  // static fills can change nothing more in the result (a third to a half
  // of the grid in a crowd is then never visited).
  std::size_t dynamic_queued = 0;
  for (const int index : queue) dynamic_queued += kind_of[index] == kDynamicOwner;
  const int neighbours[4] = {-1, 1, -stride, stride};
  for (std::size_t head = 0; head < queue.size() && dynamic_queued > 0; ++head) {
    if (head == level_end) {
      ++level;
      if (!static_started && level >= head_start) {
        add_seeds(static_seeds, kStaticOwner);
        static_started = true;
      }
      level_end = queue.size();
    }
    const int index = queue[head];
    const std::uint8_t kind = kind_of[index];
    if (kind == kDynamicOwner) --dynamic_queued;
    const int seed_index = cell[index].seed;
    Seed& seed = seeds[static_cast<std::size_t>(seed_index)];
    if (seed.pixels >= max_pixels) continue;
    const float limit2 = reach2[kind == kDynamicOwner ? 0 : 1];
    const float d = cell[index].z;
    const float max_step = step_m + step_relative * d;
    for (const int offset : neighbours) {
      const int n = index + offset;
      if (kind_of[n] != kFree) continue;  // claimed, no depth, or the border
      const Cell& c = cell[n];
      if (std::abs(c.z - d) > max_step || std::abs(c.z - seed.z) > from_seed) continue;
      if (limit2 > 0) {
        const float dx = c.x - seed.x;
        const float dy = c.y - seed.y;
        const float dz = c.z - seed.z;
        if (dx * dx + dy * dy + dz * dz > limit2) continue;
      }
      kind_of[n] = kind;
      cell[n].seed = seed_index;
      queue.push_back(n);
      dynamic_queued += kind == kDynamicOwner;
      if (++seed.pixels >= max_pixels) break;
    }
  }
  cv::Mat grid_mask;
  cv::compare(b.owner_kind(cv::Rect(1, 1, cols, rows)), kDynamicOwner, grid_mask, cv::CMP_EQ);
  if (step == 1) return grid_mask;
  // Each grid pixel stands for its step x step block.
  return image::UpsampleNearest(grid_mask, step, depth.size());
}

}  // namespace dlslam::dynamic

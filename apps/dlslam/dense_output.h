#pragma once
// `dlslam run --dense-map FILE.ply`: the dense static model of a finished
// run, written as a coloured point cloud, with what it cost and, on
// sequences with ground-truth masks, how much of the people got into it.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>

#include <opencv2/core.hpp>

#include "dlslam/dense/tsdf_volume.h"
#include "dlslam/system/slam_system.h"

namespace dlslam::app {

struct DenseMapResult {
  std::size_t points = 0;
  std::size_t blocks = 0;
  std::size_t memory_bytes = 0;
  double fuse_ms = 0.0;     // all keyframes
  double extract_ms = 0.0;  // surface extraction
  // Points fused mostly (tagged share >= 0.5) from ground-truth person
  // pixels, and their share of all points; nullopt without masks.
  std::optional<std::size_t> people_points;
  std::optional<double> people_share;
};

// Fuses, extracts and writes `path`. `people`: ground-truth person masks
// (CV_8UC1) by keyframe timestamp; empty = none.
// `with_dynamic`: fuse the removed regions too (for comparisons).
DenseMapResult WriteDenseMap(const SlamSystem& slam, const dense::TsdfOptions& options,
                             const std::map<double, cv::Mat>& people, const std::filesystem::path& path,
                             bool with_dynamic = false);

nlohmann::ordered_json DenseMapReport(const DenseMapResult& result);

}  // namespace dlslam::app

#include "dense_output.h"

#include <spdlog/spdlog.h>

#include "dlslam/io/ply_writer.h"
#include "dlslam/util/timing.h"
#include "run_report.h"

namespace dlslam::app {

DenseMapResult WriteDenseMap(const SlamSystem& slam, const dense::TsdfOptions& options,
                             const std::map<double, cv::Mat>& people, const std::filesystem::path& path,
                             bool with_dynamic) {
  DenseMapResult result;
  Stopwatch watch;
  const auto tag = [&people](double timestamp) {
    const auto it = people.find(timestamp);
    return it == people.end() ? cv::Mat() : it->second;
  };
  const dense::TsdfVolume volume = slam.FuseDenseMap(options, people.empty() ? nullptr : std::function(tag), !with_dynamic);
  result.fuse_ms = watch.ElapsedMs();
  watch = Stopwatch();
  const std::vector<dense::SurfacePoint> surface = volume.ExtractSurface();
  result.extract_ms = watch.ElapsedMs();
  result.points = surface.size();
  result.blocks = volume.NumBlocks();
  result.memory_bytes = volume.MemoryBytes();
  std::vector<io::ColouredPoint> cloud;
  cloud.reserve(surface.size());
  std::size_t tagged = 0;
  for (const dense::SurfacePoint& p : surface) {
    cloud.push_back({p.position, {p.bgr[2], p.bgr[1], p.bgr[0]}});
    tagged += p.tagged_share >= 0.5f;
  }
  if (!people.empty()) {
    result.people_points = tagged;
    result.people_share = surface.empty() ? 0.0 : static_cast<double>(tagged) / static_cast<double>(surface.size());
  }
  io::WritePointCloudPly(path, cloud);
  spdlog::info("dense map: {} points ({} blocks of {:.2f} m voxels, {:.0f} MB) in {}; fused in {:.0f} ms, "
               "extracted in {:.0f} ms{}",
               result.points, result.blocks, options.voxel_size, static_cast<double>(result.memory_bytes) / 1e6,
               path.string(), result.fuse_ms, result.extract_ms,
               result.people_share ? fmt::format("; {:.2f} % of the points from ground-truth people",
                                                 100.0 * *result.people_share)
                                   : std::string());
  return result;
}

nlohmann::ordered_json DenseMapReport(const DenseMapResult& result) {
  nlohmann::ordered_json j;
  j["points"] = result.points;
  j["blocks"] = result.blocks;
  j["memory_bytes"] = result.memory_bytes;
  j["fuse_ms"] = result.fuse_ms;
  j["extract_ms"] = result.extract_ms;
  j["people_points"] = OrNull(result.people_points);
  j["people_share"] = OrNull(result.people_share);
  return j;
}

}  // namespace dlslam::app

#pragma once
// `dlslam run --html report.html`: the run as one self-contained page (no
// network, no files beside it): summary, trajectory against ground truth
// coloured by how each pose was obtained, the ATE over time, the map points
// and keyframes in 3-D (drag to orbit, wheel to zoom), per-stage timings,
// the effective options.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "dlslam/system/slam_system.h"
#include "run_report.h"

namespace dlslam::app {

struct HtmlReportInput {
  std::string title;                      // e.g. the sequence folder's name
  const SlamSystem* slam = nullptr;       // finished (after Shutdown)
  const RunStats* stats = nullptr;
  const std::optional<RunEvaluation>* evaluation = nullptr;
  nlohmann::ordered_json options;         // config::ConfigJson
};

// What the page draws, in its units: a position in mm; at most 30,000 of
// the map's points (evenly subsampled), each through `place` (into the
// ground truth's frame) first.
nlohmann::ordered_json PositionMm(const Eigen::Vector3d& p);
nlohmann::ordered_json MapPointsMm(const std::vector<Eigen::Vector3d>& points,
                                   const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& place);

// The page's data (what the page draws), kept small: positions in mm, at
// most 30,000 map points.
nlohmann::ordered_json HtmlReportData(const HtmlReportInput& input);
// The page itself with `data` embedded.
std::string HtmlReportPage(const nlohmann::ordered_json& data);
// Writes the page atomically; throws InputError.
void WriteHtmlReport(const std::filesystem::path& path, const HtmlReportInput& input);

}  // namespace dlslam::app

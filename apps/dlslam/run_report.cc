#include "run_report.h"

#include <spdlog/spdlog.h>

#include "dlslam/eval/report.h"
#include "dlslam/util/check.h"

namespace dlslam::app {

nlohmann::ordered_json MakeRunReport(const RunStats& stats, const std::optional<RunEvaluation>& evaluation) {
  nlohmann::ordered_json j;
  j["frames"] = stats.frames;
  j["frames_tracked"] = stats.frames_tracked;
  j["frames_lost"] = stats.frames_lost;
  j["frames_waiting"] = stats.frames_waiting;
  j["keyframes"] = stats.keyframes;
  j["map_points"] = stats.map_points;
  j["local_mapping"] = {{"keyframes_processed", stats.mapping.keyframes_processed},
                        {"points_culled", stats.mapping.points_culled},
                        {"points_triangulated", stats.mapping.points_triangulated},
                        {"points_fused", stats.mapping.points_fused},
                        {"keyframes_culled", stats.mapping.keyframes_culled},
                        {"bundle_outliers", stats.mapping.bundle_outliers}};
  nlohmann::ordered_json timing;
  for (const auto& [stage, s] : stats.timing_ms) {
    timing[stage] = {{"median", s.median}, {"p95", s.p95}, {"max", s.max}, {"count", s.count}};
  }
  j["timing_ms"] = timing;
  if (evaluation) {
    j["ate"] = eval::ToJson(evaluation->ate);
    if (evaluation->rpe) j["rpe"] = eval::ToJson(*evaluation->rpe);
  }
  return j;
}

std::optional<RunEvaluation> EvaluateRun(const Trajectory& ground_truth, const Trajectory& estimate) {
  if (estimate.size() < 2) {
    spdlog::warn("evaluation skipped: only {} tracked frame(s)", estimate.size());
    return std::nullopt;
  }
  RunEvaluation out;
  try {
    out.ate = eval::ComputeAte(ground_truth, estimate);
  } catch (const Error& e) {
    spdlog::warn("ATE not computed: {}", e.what());
    return std::nullopt;
  }
  try {
    out.rpe = eval::ComputeRpe(ground_truth, estimate);
  } catch (const Error& e) {
    spdlog::warn("RPE not computed: {}", e.what());
  }
  return out;
}

}  // namespace dlslam::app

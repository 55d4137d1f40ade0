#pragma once
// The JSON report of a run (`dlslam run --report FILE`).

#include <nlohmann/json.hpp>

#include <optional>

#include "dlslam/eval/ate.h"
#include "dlslam/eval/rpe.h"
#include "dlslam/system/slam_system.h"

namespace dlslam::app {

struct RunEvaluation {
  eval::AteResult ate;
  std::optional<eval::RpeResult> rpe;  // absent when the run is shorter than the delta
};

// Keys: frames, frames_tracked, frames_lost, frames_waiting, keyframes,
// map_points, local_mapping {...}, timing_ms {stage: {median, p95, max,
// count}}, and, with ground truth, ate / rpe as `dlslam eval --json`.
nlohmann::ordered_json MakeRunReport(const RunStats& stats, const std::optional<RunEvaluation>& evaluation);

// Evaluates against ground truth when there is enough overlap; nullopt (and a
// warning) otherwise.
std::optional<RunEvaluation> EvaluateRun(const Trajectory& ground_truth, const Trajectory& estimate);

}  // namespace dlslam::app

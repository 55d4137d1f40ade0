#pragma once
// The JSON report of a run (`dlslam run --report FILE`).

#include <nlohmann/json.hpp>

#include <optional>

#include "dlslam/eval/ate.h"
#include "dlslam/eval/rpe.h"
#include "dlslam/system/slam_system.h"

namespace dlslam::app {

// Accuracy against the ground truth as published (the TUM tool's numbers;
// for Bonn RGB-D Dynamic the motion-capture marker's poses) and, for Bonn,
// against the camera's poses too (eval::GroundTruthConvention::kBonnCamera:
// what the dataset's tools compare, and the only meaningful RPE there).
struct TrajectoryAccuracy {
  eval::AteResult ate;
  std::optional<eval::RpeResult> rpe;  // absent when the run is shorter than the delta
};
struct RunEvaluation : TrajectoryAccuracy {  // as published
  std::optional<TrajectoryAccuracy> bonn_camera;
};

// Keys: frames, frames_tracked, frames_lost, frames_waiting, keyframes,
// map_points, local_mapping {...}, timing_ms {stage: {median, p95, max,
// count}}, dynamic {...} (DynamicReport), and, with ground truth, ate / rpe
// as `dlslam eval --json`.
nlohmann::ordered_json MakeRunReport(const RunStats& stats, const std::optional<RunEvaluation>& evaluation);

// The "dynamic" object: mode, search, fusion (mode full), keypoints_total,
// keypoints_tested,
// keypoints_dynamic, keypoints_removed, frames_with_geometry,
// map_points_culled, geometry_ms / semantic_ms / semantic_wait_ms {median,
// p95, max} (null when the stage never ran), and with ground-truth masks
// frames_with_truth, precision, recall (null when undefined), true_positives,
// false_positives, false_negatives.
nlohmann::ordered_json DynamicReport(const RunStats& stats);

// `v` as JSON, or null without a value.
template <class T>
nlohmann::ordered_json OrNull(const std::optional<T>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

// How the frames' poses were obtained: {tracked, relocalized, coasted, new_map, none}.
nlohmann::ordered_json PoseSourcesReport(const RunStats& stats);
// One letter per pose source for the report page and the live view:
// t tracked, r relocalized, c coasted, n new map (before its merge), - none.
char PoseSourceLetter(PoseSource source);
// Per stage: {median, p95, count} [ms].
nlohmann::ordered_json TimingsReport(const std::map<std::string, TimingSummary>& timings);

// Evaluates against ground truth when there is enough overlap; nullopt (and a
// warning) otherwise.
// `bonn`: the ground truth is a Bonn RGB-D Dynamic marker trajectory (the
// sequence's camera is the Bonn preset): evaluate against its camera poses too.
std::optional<RunEvaluation> EvaluateRun(const Trajectory& ground_truth, const Trajectory& estimate,
                                         bool bonn = false);

}  // namespace dlslam::app

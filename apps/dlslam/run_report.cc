#include "run_report.h"

#include <spdlog/spdlog.h>

#include "dlslam/eval/ground_truth_convention.h"
#include "dlslam/eval/report.h"
#include "dlslam/util/check.h"

namespace dlslam::app {

namespace {

nlohmann::ordered_json StageSummary(const RunStats& stats, const std::string& stage) {
  const auto it = stats.timing_ms.find(stage);
  if (it == stats.timing_ms.end()) return nullptr;
  return {{"median", it->second.median}, {"p95", it->second.p95}, {"max", it->second.max}};
}

}  // namespace

nlohmann::ordered_json DynamicReport(const RunStats& stats) {
  const DynamicStats& d = stats.dynamic;
  nlohmann::ordered_json j;
  j["mode"] = ToString(d.mode);
  j["search"] = dynamic::ToString(d.search);
  if (d.mode == DynamicMode::kFull) j["fusion"] = dynamic::ToString(d.fusion);
  j["keypoints_total"] = d.keypoints_total;
  j["keypoints_tested"] = d.keypoints_tested;
  j["keypoints_dynamic"] = d.keypoints_dynamic;
  j["keypoints_removed"] = d.keypoints_removed;
  j["image_share_removed"] = OrNull(d.image_share_removed());
  j["frames_with_geometry"] = d.frames_with_geometry;
  j["map_points_culled"] = d.map_points_culled;
  j["movable_segments_dropped"] = d.movable_segments_dropped;
  j["inverted_checks_tried"] = d.inverted_checks_tried;
  j["inverted_checks_resolved"] = d.inverted_checks_resolved;
  j["geometry_overruled"] = d.geometry_overruled;
  j["free_space_frames"] = d.free_space_frames;
  j["free_space_views_ignored"] = d.free_space_views_ignored;
  j["free_space_image_share"] =
      d.free_space_frames > 0 ? nlohmann::ordered_json(d.free_space_share_sum / static_cast<double>(d.free_space_frames))
                              : nlohmann::ordered_json();
  j["free_space_ms"] = StageSummary(stats, "free_space");
  j["geometry_ms"] = StageSummary(stats, "geometry");
  j["semantic_ms"] = StageSummary(stats, "semantic");
  j["semantic_wait_ms"] = StageSummary(stats, "semantic_wait");
  if (d.frames_with_truth > 0) {
    j["frames_with_truth"] = d.frames_with_truth;
    j["precision"] = OrNull(d.precision());
    j["recall"] = OrNull(d.recall());
    j["true_positives"] = d.true_positives;
    j["false_positives"] = d.false_positives;
    j["false_negatives"] = d.false_negatives;
  }
  return j;
}

namespace {

nlohmann::ordered_json LoopReport(const LoopClosingStats& loop) {
  nlohmann::ordered_json j;
  j["keyframes_checked"] = loop.keyframes_checked;
  j["keyframes_skipped"] = loop.keyframes_skipped;
  j["consistent_candidates"] = loop.consistent_candidates;
  j["rejected"] = loop.loops_rejected;
  j["global_bundles_completed"] = loop.global_bundles_completed;
  j["global_bundles_aborted"] = loop.global_bundles_aborted;
  nlohmann::ordered_json loops = nlohmann::ordered_json::array();
  for (const LoopEvent& e : loop.loops) {
    loops.push_back({{"keyframe", e.current},
                     {"loop_keyframe", e.loop},
                     {"timestamp", e.current_timestamp},
                     {"loop_timestamp", e.loop_timestamp},
                     {"inliers", e.inliers},
                     {"correction_m", e.correction.correction_m},
                     {"correction_deg", e.correction.correction_deg},
                     {"keyframes_moved", e.correction.keyframes_moved},
                     {"points_fused", e.correction.points_fused}});
  }
  j["loops"] = loops;
  return j;
}

}  // namespace

nlohmann::ordered_json PoseSourcesReport(const RunStats& stats) {
  return {{"tracked", stats.frames_tracked_source()},
          {"relocalized", stats.relocalizations},
          {"coasted", stats.frames_coasted},
          {"new_map", stats.frames_new_map},
          {"none", stats.frames_without_pose()}};
}

char PoseSourceLetter(PoseSource source) {
  switch (source) {
    case PoseSource::kTracked: return 't';
    case PoseSource::kRelocalized: return 'r';
    case PoseSource::kCoasted: return 'c';
    case PoseSource::kNewMap: return 'n';
    case PoseSource::kNone: return '-';
  }
  return '-';
}

nlohmann::ordered_json TimingsReport(const std::map<std::string, TimingSummary>& timings) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [stage, s] : timings) {
    j[stage] = {{"median", s.median}, {"p95", s.p95}, {"max", s.max}, {"count", s.count}};
  }
  return j;
}

namespace {

// "ground_truth", "ate" and (when computed) "rpe" into `out`.
void AddAccuracy(const TrajectoryAccuracy& accuracy, eval::GroundTruthConvention convention,
                 nlohmann::ordered_json* out) {
  (*out)["ground_truth"] = eval::ToString(convention);
  (*out)["ate"] = eval::ToJson(accuracy.ate);
  if (accuracy.rpe) (*out)["rpe"] = eval::ToJson(*accuracy.rpe);
}

}  // namespace

nlohmann::ordered_json MakeRunReport(const RunStats& stats, const std::optional<RunEvaluation>& evaluation) {
  nlohmann::ordered_json j;
  j["frames"] = stats.frames;
  j["frames_posed"] = stats.frames_posed();
  j["frames_tracked"] = stats.frames_tracked;
  j["frames_coasted"] = stats.frames_coasted;
  j["frames_lost"] = stats.frames_lost;
  j["pose_sources"] = PoseSourcesReport(stats);
  j["frames_extracted_outside_prior"] = stats.frames_extracted_outside_prior;
  j["frames_reextracted"] = stats.frames_reextracted;
  j["maps_started"] = stats.maps_started;
  j["maps_merged"] = stats.maps_merged;
  j["relocalizations"] = stats.relocalizations;
  j["jumps_refused"] = stats.jumps_refused;
  j["frames_gated"] = stats.frames_gated;
  j["frames_segmented_ahead"] = stats.frames_segmented_ahead;
  j["keyframes_held_for_masks"] = {{"held", stats.keyframes_held},
                                   {"dropped", stats.keyframes_held_dropped},
                                   {"keypoints_masked", stats.keyframe_keypoints_masked_late}};
  j["loops_closed"] = stats.loop.loops_closed;
  j["frames_waiting"] = stats.frames_waiting;
  j["frames_dropped"] = stats.frames_dropped;
  j["keyframes"] = stats.keyframes;
  j["map_points"] = stats.map_points;
  j["local_mapping"] = {{"keyframes_processed", stats.mapping.keyframes_processed},
                        {"points_culled", stats.mapping.points_culled},
                        {"points_triangulated", stats.mapping.points_triangulated},
                        {"points_fused", stats.mapping.points_fused},
                        {"keyframes_culled", stats.mapping.keyframes_culled},
                        {"bundle_outliers", stats.mapping.bundle_outliers},
                        {"bundles_yielded", stats.mapping.bundles_yielded}};
  j["loop_closing"] = LoopReport(stats.loop);
  j["timing_ms"] = TimingsReport(stats.timing_ms);
  j["dynamic"] = DynamicReport(stats);
  if (evaluation) {
    AddAccuracy(*evaluation, eval::GroundTruthConvention::kAsPublished, &j);
    if (const auto& camera = evaluation->bonn_camera) {
      AddAccuracy(*camera, eval::GroundTruthConvention::kBonnCamera, &j["bonn_camera"]);
    }
  }
  return j;
}

namespace {

// ATE and RPE against `ground_truth`; nullopt without an ATE. Failures are
// warned about when `warn` (the conventions pair the same poses: a second
// warning would only repeat the first).
std::optional<TrajectoryAccuracy> Accuracy(const Trajectory& ground_truth, const Trajectory& estimate, bool warn) {
  TrajectoryAccuracy out;
  try {
    out.ate = eval::ComputeAte(ground_truth, estimate);
  } catch (const Error& e) {
    if (warn) spdlog::warn("ATE not computed: {}", e.what());
    return std::nullopt;
  }
  try {
    out.rpe = eval::ComputeRpe(ground_truth, estimate);
  } catch (const Error& e) {
    if (warn) spdlog::warn("RPE not computed: {}", e.what());
  }
  return out;
}

}  // namespace

std::optional<RunEvaluation> EvaluateRun(const Trajectory& ground_truth, const Trajectory& estimate, bool bonn) {
  if (estimate.size() < 2) {
    spdlog::warn("evaluation skipped: only {} tracked frame(s)", estimate.size());
    return std::nullopt;
  }
  std::optional<TrajectoryAccuracy> published = Accuracy(ground_truth, estimate, /*warn=*/true);
  if (!published) return std::nullopt;
  RunEvaluation out;
  static_cast<TrajectoryAccuracy&>(out) = std::move(*published);
  if (bonn) {
    out.bonn_camera = Accuracy(eval::ToCameraPoses(ground_truth, eval::GroundTruthConvention::kBonnCamera), estimate,
                               /*warn=*/false);
  }
  return out;
}

}  // namespace dlslam::app

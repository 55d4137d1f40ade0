#include "dlslam/loop/loop_closer.h"

#include <spdlog/spdlog.h>

#include "dlslam/util/check.h"
#include "dlslam/util/thread_priority.h"

namespace dlslam {

void LoopClosingOptions::Check() const {
  detection.Check();
  correction.Check();
  global_bundle.Check();
  DLSLAM_CHECK_GT(queue_capacity, 0u);
  DLSLAM_CHECK(thread_nice >= 0 && thread_nice <= 19, "thread_nice {} must be in 0..19", thread_nice);
}

LoopCloser::LoopCloser(const LoopClosingOptions& options, Map* map, const place::KeyFrameIndex* index,
                       LocalMapper* mapper, StageTimings* timings)
    : options_(options),
      map_(map),
      mapper_(mapper),
      timings_(timings),
      detector_(options.detection, map, index),
      queue_(options.queue_capacity) {
  options_.Check();
  DLSLAM_CHECK(map_ != nullptr && mapper_ != nullptr);
}

LoopCloser::~LoopCloser() { Stop(); }

void LoopCloser::Start() {
  DLSLAM_CHECK(!thread_.joinable(), "loop closing already started");
  thread_ = std::thread([this] { Run(); });
}

void LoopCloser::Enqueue(KeyFrameId keyframe) {
  if (!thread_.joinable()) {
    ProcessGuarded(keyframe);
    return;
  }
  if (!queue_.TryPush(keyframe)) {
    std::lock_guard lock(stats_mutex_);
    ++stats_.keyframes_skipped;
  }
}

void LoopCloser::Stop() {
  queue_.Stop();
  if (thread_.joinable()) thread_.join();
  if (bundle_thread_.joinable()) bundle_thread_.join();
}

LoopClosingStats LoopCloser::stats() const {
  std::lock_guard lock(stats_mutex_);
  return stats_;
}

void LoopCloser::Run() {
  LowerBackgroundPriority(options_.thread_nice, "loop closing");
  while (const std::optional<KeyFrameId> keyframe = queue_.Pop()) ProcessGuarded(*keyframe);
}

void LoopCloser::ProcessGuarded(KeyFrameId keyframe) {
  try {
    Process(keyframe);
  } catch (const std::exception& e) {
    // A failed loop must not take tracking down: the map stays as it was
    // left, which the next loop or bundle adjustment can still repair.
    spdlog::warn("loop closing at keyframe {} failed: {}", keyframe, e.what());
  }
}

void LoopCloser::Process(KeyFrameId keyframe) {
  Stopwatch watch;
  const LoopDetection detection = detector_.Process(keyframe);
  if (timings_) timings_->Add("loop_detection", watch.ElapsedMs());
  {
    std::lock_guard lock(stats_mutex_);
    stats_.keyframes_checked += detection.outcome != LoopOutcome::kTooEarly;
    stats_.consistent_candidates += detection.verified;
    stats_.loops_rejected += detection.outcome == LoopOutcome::kRejected;
  }
  if (!detection.match) return;
  const LoopMatch& loop = *detection.match;

  AbortGlobalBundle();  // its result would undo this correction
  watch = Stopwatch();
  LoopCorrection correction;
  {
    const PauseGate::Hold paused = mapper_->Pause();
    if (timings_) timings_->Add("loop_wait_for_mapping", watch.ElapsedMs());
    watch = Stopwatch();
    correction = CloseLoop(map_, loop, options_.correction);
  }
  if (timings_) timings_->Add("loop_correction", watch.ElapsedMs());
  detector_.LoopClosedAt(keyframe);
  LoopEvent event{loop.current, loop.loop, 0.0, 0.0, loop.inliers, correction};
  if (const auto k = map_->GetKeyFrame(loop.current)) event.current_timestamp = k->frame->timestamp();
  if (const auto k = map_->GetKeyFrame(loop.loop)) event.loop_timestamp = k->frame->timestamp();
  spdlog::info("loop closed: keyframe {} (t={:.3f}) sees keyframe {} (t={:.3f}), {} inliers; drift {:.3f} m, "
               "{:.2f} deg; {} keyframes moved, {} points fused",
               loop.current, event.current_timestamp, loop.loop, event.loop_timestamp, loop.inliers,
               correction.correction_m, correction.correction_deg, correction.keyframes_moved,
               correction.points_fused);
  {
    std::lock_guard lock(stats_mutex_);
    ++stats_.loops_closed;
    stats_.loops.push_back(event);
  }
  if (!options_.global_bundle_adjustment) return;
  abort_bundle_ = false;
  if (thread_.joinable()) {
    bundle_thread_ = std::thread([this] { RunGlobalBundle(); });
  } else {
    RunGlobalBundle();
  }
}

void LoopCloser::AbortGlobalBundle() {
  if (!bundle_thread_.joinable()) return;
  abort_bundle_ = true;
  bundle_thread_.join();
}

void LoopCloser::RunGlobalBundle() {
  LowerBackgroundPriority(options_.thread_nice, "global bundle adjustment");
  try {
    const Stopwatch watch;
    const std::uint64_t generation = map_->Generation();
    LocalBundle bundle = map_->BuildGlobalBundle();
    BundleAdjusterOptions options = options_.global_bundle;
    options.abort = &abort_bundle_;
    const BundleSummary summary = SolveBundle(&bundle.problem, options);
    if (summary.aborted) {
      std::lock_guard lock(stats_mutex_);
      ++stats_.global_bundles_aborted;
      return;
    }
    {
      const PauseGate::Hold paused = mapper_->Pause();
      if (map_->Generation() != generation) {
        // The map moved meanwhile (a new map merged into an older one):
        // writing back poses from before would undo that.
        std::lock_guard lock(stats_mutex_);
        ++stats_.global_bundles_aborted;
        return;
      }
      map_->ApplyGlobalBundle(bundle, summary.outlier);
    }
    if (timings_) timings_->Add("global_bundle_adjustment", watch.ElapsedMs());
    spdlog::debug("global bundle adjustment: {} keyframes, {} points, cost {:.4g} -> {:.4g}, {:.0f} ms",
                  bundle.pose_ids.size(), bundle.point_ids.size(), summary.initial_cost, summary.final_cost,
                  watch.ElapsedMs());
    std::lock_guard lock(stats_mutex_);
    ++stats_.global_bundles_completed;
  } catch (const std::exception& e) {
    spdlog::warn("global bundle adjustment failed: {}", e.what());
  }
}

}  // namespace dlslam

#include "dlslam/mapping/local_mapper.h"

#include <spdlog/spdlog.h>

#include "dlslam/util/check.h"
#include "dlslam/util/thread_priority.h"

namespace dlslam {

void LocalMapperOptions::Check() const {
  DLSLAM_CHECK_GT(queue_capacity, 0u);
  DLSLAM_CHECK_GE(min_point_observations, 1);
  DLSLAM_CHECK(min_found_ratio >= 0 && min_found_ratio <= 1);
  DLSLAM_CHECK(keyframe_redundancy > 0 && keyframe_redundancy <= 1);
  DLSLAM_CHECK_GT(close_depth, 0.0);
  DLSLAM_CHECK(thread_nice >= 0 && thread_nice <= 19, "thread_nice {} must be in 0..19", thread_nice);
  DLSLAM_CHECK(max_bundle_yields_in_a_row >= 0, "max_bundle_yields_in_a_row {} must be >= 0", max_bundle_yields_in_a_row);
  triangulate.Check();
  fuse.Check();
  bundle.Check();
}

LocalMapper::LocalMapper(const LocalMapperOptions& options, Map* map, StageTimings* timings, KeyFrameHooks hooks)
    : options_(options), map_(map), timings_(timings), hooks_(std::move(hooks)), queue_(options.queue_capacity) {
  options_.Check();
  DLSLAM_CHECK(map_ != nullptr);
}

LocalMapper::~LocalMapper() { Stop(); }

void LocalMapper::Start() {
  DLSLAM_CHECK(!thread_.joinable(), "local mapping already started");
  threaded_ = true;  // before the thread: it reads it
  thread_ = std::thread([this] { Run(); });
}

std::uint64_t LocalMapper::Enqueue(KeyFrameId keyframe) {
  ++enqueued_;
  if (!thread_.joinable()) {
    ProcessAndHandOver(keyframe);
    std::lock_guard lock(processed_mutex_);
    processed_ = enqueued_;
    return enqueued_;
  }
  queue_.Push(keyframe);
  keyframe_queued_ = true;
  return enqueued_;
}

bool LocalMapper::WaitForProcessed(std::uint64_t ticket, std::chrono::nanoseconds timeout) {
  std::unique_lock lock(processed_mutex_);
  return processed_changed_.wait_for(lock, timeout, [&] { return processed_ >= ticket; });
}

PauseGate::Hold LocalMapper::Pause() { return pause_gate_.Pause(); }

void LocalMapper::ProcessAndHandOver(KeyFrameId keyframe) {
  {
    const PauseGate::Hold step = pause_gate_.BeginStep();
    Process(keyframe);
  }
  if (hooks_.processed) hooks_.processed(keyframe);
}

void LocalMapper::Stop() {
  queue_.Stop();
  if (thread_.joinable()) thread_.join();
}

void LocalMapper::Run() {
  LowerBackgroundPriority(options_.thread_nice, "local mapping");
  while (const std::optional<KeyFrameId> keyframe = queue_.Pop()) {
    try {
      ProcessAndHandOver(*keyframe);
    } catch (const std::exception& e) {
      // A failed refinement must not take tracking down: the keyframe stays
      // as tracking made it.
      spdlog::warn("local mapping of keyframe {} failed: {}", *keyframe, e.what());
    }
    {
      std::lock_guard lock(processed_mutex_);
      ++processed_;
    }
    processed_changed_.notify_all();
  }
}

LocalMappingStats LocalMapper::stats() const {
  std::lock_guard lock(stats_mutex_);
  return stats_;
}

void LocalMapper::Process(KeyFrameId keyframe) {
  const std::optional<KeyFrameSnapshot> snapshot = map_->GetKeyFrame(keyframe);
  if (!snapshot) return;  // culled while queued
  Stopwatch total;
  if (hooks_.added) {
    Stopwatch watch;
    hooks_.added(*snapshot);
    if (timings_) timings_->Add("keyframe_bow", watch.ElapsedMs());
  }
  LocalMappingStats step;
  step.points_culled = map_->CullRecentPoints(keyframe, options_.min_point_observations, options_.min_found_ratio);
  if (options_.triangulation) {
    Stopwatch watch;
    step.points_triangulated = CreateNewMapPoints(map_, keyframe, options_.triangulate);
    if (timings_) timings_->Add("triangulation", watch.ElapsedMs());
  }
  if (options_.fusion) {
    Stopwatch watch;
    step.points_fused = FuseWithNeighbours(map_, keyframe, options_.fuse).fused;
    if (timings_) timings_->Add("fusion", watch.ElapsedMs());
  }
  if (options_.bundle_adjustment) {
    Stopwatch ba;
    LocalBundle bundle = map_->BuildLocalBundle(keyframe);
    BundleAdjusterOptions bundle_options = options_.bundle;
    if (threaded_ && bundles_yielded_in_a_row_ < options_.max_bundle_yields_in_a_row) {
      keyframe_queued_ = queue_.size() > 0;
      bundle_options.abort = &keyframe_queued_;
    }
    const BundleSummary summary = SolveBundle(&bundle.problem, bundle_options);
    map_->ApplyLocalBundle(bundle, summary.outlier);
    step.bundle_outliers = summary.outliers;
    step.bundles_yielded = summary.aborted ? 1 : 0;
    bundles_yielded_in_a_row_ = summary.aborted ? bundles_yielded_in_a_row_ + 1 : 0;
    if (timings_) timings_->Add("local_bundle_adjustment", ba.ElapsedMs());
  }
  const std::vector<KeyFrameId> culled =
      map_->CullRedundantKeyFrames(keyframe, options_.close_depth, options_.keyframe_redundancy);
  if (hooks_.culled) {
    for (KeyFrameId id : culled) hooks_.culled(id);
  }
  step.keyframes_culled = static_cast<int>(culled.size());
  map_->UpdateConnections(keyframe);
  if (timings_) timings_->Add("local_mapping", total.ElapsedMs());
  std::lock_guard lock(stats_mutex_);
  ++stats_.keyframes_processed;
  stats_.points_culled += step.points_culled;
  stats_.points_triangulated += step.points_triangulated;
  stats_.points_fused += step.points_fused;
  stats_.keyframes_culled += step.keyframes_culled;
  stats_.bundle_outliers += step.bundle_outliers;
  stats_.bundles_yielded += step.bundles_yielded;
}

}  // namespace dlslam

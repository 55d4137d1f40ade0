#pragma once
// Local mapping: refines the map around each new keyframe, in its own thread
// (or inline, for the deterministic sequential mode). Per keyframe: cull the
// recent points tracking rarely finds, triangulate new points with the
// neighbours, fuse duplicated points across them, local bundle adjustment,
// cull redundant keyframes. Keyframes arrive through a bounded queue; the thread
// owns no map state of its own.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

#include "dlslam/map/map.h"
#include "dlslam/mapping/fusion.h"
#include "dlslam/mapping/triangulation.h"
#include "dlslam/optimize/bundle_adjuster.h"
#include "dlslam/util/bounded_queue.h"
#include "dlslam/util/pause_gate.h"
#include "dlslam/util/timing.h"

namespace dlslam {

struct LocalMapperOptions {
  // Keyframes waiting for local mapping; tracking blocks when it is full.
  std::size_t queue_capacity = 8;
  // A recent point needs this many keyframes observing it. (ORB-SLAM keeps
  // RGB-D points with more than 3 observations, counting one with depth as
  // two: i.e. two keyframes.)
  int min_point_observations = 2;
  // ... and tracking must find it in this fraction of the frames it should.
  double min_found_ratio = 0.25;
  // Keyframes whose close points are this redundant are culled (ORB-SLAM: 0.9).
  double keyframe_redundancy = 0.9;
  // Keypoints closer than this [m] have reliable depth (see TrackerOptions).
  double close_depth = 3.0;
  // New points by triangulation with the neighbouring keyframes.
  bool triangulation = true;
  TriangulationOptions triangulate;
  // Fusion of duplicated points across neighbouring keyframes.
  bool fusion = true;
  FusionOptions fuse;
  bool bundle_adjustment = true;
  BundleAdjusterOptions bundle;
  // Threaded: a local bundle adjustment stops at its next iteration when a
  // new keyframe is queued (ORB-SLAM's behaviour), so the new keyframe's
  // points reach tracking sooner; what it refined so far is kept. At most
  // this many in a row (a starved mapper, keyframes always queued, would
  // refine nothing otherwise); 0 = never. Bonn full threaded, interleaved:
  // 3 in a row 0.0146-0.0186 m (median 0.0160) in 12 runs, unlimited
  // 0.0149-0.0170 m in 7, once in a row 0.0154-0.0183 m in 6, never
  // 0.0148-0.0203 m (median 0.0176) in 25; the same pace (docs/speed.md).
  int max_bundle_yields_in_a_row = 3;
  // How much lower than the caller's the thread's CPU priority is (nice
  // increment, 0..19; util/thread_priority.h): with fewer free cores than
  // busy threads the tracker then gets a core first. 10: Bonn full
  // threaded, 4 interleaved pairs, real-time factor 1.38-1.41x vs 1.27-1.34x
  // (with loop closing's), the same ATE (docs/speed.md).
  int thread_nice = 10;

  void Check() const;
};

struct LocalMappingStats {
  int keyframes_processed = 0;
  int points_culled = 0;
  int points_triangulated = 0;
  int points_fused = 0;  // observations added or points merged by fusion
  int keyframes_culled = 0;
  int bundle_outliers = 0;
  int bundles_yielded = 0;  // local bundle adjustments stopped early for a queued keyframe
};

// Called on the mapping thread for each keyframe local mapping takes on and
// each one it culls: how the place-recognition index stays beside the map
// without the map knowing of it. Must not call back into the mapper.
struct KeyFrameHooks {
  std::function<void(const KeyFrameSnapshot&)> added;
  std::function<void(KeyFrameId)> culled;
  // After a keyframe is finished, outside its pause-gate step (loop closing
  // hands itself the keyframe here, and may pause the mapper inline).
  std::function<void(KeyFrameId)> processed;
};

class LocalMapper {
 public:
  // `timings` (optional, outlives the mapper) receives per-step durations.
  LocalMapper(const LocalMapperOptions& options, Map* map, StageTimings* timings = nullptr, KeyFrameHooks hooks = {});
  ~LocalMapper();
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  // Starts the thread. Without it, Enqueue processes inline (sequential mode).
  void Start();
  // Hands a new keyframe over; blocks while the queue is full. Returns how
  // many keyframes were handed over so far, this one included (its ticket
  // for WaitForProcessed).
  std::uint64_t Enqueue(KeyFrameId keyframe);
  // Blocks until the first `ticket` keyframes handed over are processed (at
  // once when they are, or without the thread), at most `timeout`. Returns
  // whether they are.
  bool WaitForProcessed(std::uint64_t ticket, std::chrono::nanoseconds timeout);
  // Finishes the queued keyframes, then joins the thread.
  void Stop();
  // Holds local mapping between two keyframes for as long as the returned
  // hold lives (waits for the keyframe in progress, never for the queued
  // ones): loop closing moves the map meanwhile. Tracking is not held;
  // keyframes queue up.
  [[nodiscard]] PauseGate::Hold Pause();

  LocalMappingStats stats() const;
  // Keyframes handed over and not yet taken on (the one in progress excluded).
  std::size_t backlog() const { return queue_.size(); }

 private:
  // Process as one step of the pause gate, then the `processed` hook.
  void ProcessAndHandOver(KeyFrameId keyframe);
  void Process(KeyFrameId keyframe);
  void Run();

  LocalMapperOptions options_;
  Map* map_;
  StageTimings* timings_;
  KeyFrameHooks hooks_;
  BoundedQueue<KeyFrameId> queue_;
  std::atomic<bool> keyframe_queued_{false};  // set by Enqueue, cleared before each bundle adjustment
  bool threaded_ = false;                      // Start was called
  int bundles_yielded_in_a_row_ = 0;           // the mapper thread's own
  std::uint64_t enqueued_ = 0;                 // Enqueue's caller's own
  std::mutex processed_mutex_;
  std::condition_variable processed_changed_;
  std::uint64_t processed_ = 0;  // keyframes finished (or culled while queued, or failed): WaitForProcessed
  std::thread thread_;
  PauseGate pause_gate_;  // a keyframe's processing is one step
  mutable std::mutex stats_mutex_;
  LocalMappingStats stats_;
};

}  // namespace dlslam

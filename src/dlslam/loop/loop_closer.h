#pragma once
// The loop-closing thread. Local mapping hands over each keyframe it has
// finished; for each, the detector looks for a loop (loop_detector.h); a
// verified loop is closed in the map with local mapping paused
// (loop_correction.h) while tracking goes on; then a full bundle adjustment
// runs in a thread of its own, which the next loop interrupts.
//
// Ownership: the closer owns its queue, its detector and the bundle thread;
// the map, the keyframe index and the local mapper belong to the system.
// Without Start() everything runs inline in Enqueue (sequential mode,
// reproducible bit for bit).

#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "dlslam/loop/loop_correction.h"
#include "dlslam/loop/loop_detector.h"
#include "dlslam/mapping/local_mapper.h"
#include "dlslam/optimize/bundle_adjuster.h"
#include "dlslam/util/bounded_queue.h"
#include "dlslam/util/timing.h"

namespace dlslam {

struct LoopClosingOptions {
  LoopDetectorOptions detection;
  LoopCorrectionOptions correction;
  // A full bundle adjustment after each closed loop, in the background.
  bool global_bundle_adjustment = true;
  BundleAdjusterOptions global_bundle;
  // Keyframes waiting for loop detection [count]; when it is full, local
  // mapping does not wait: the keyframe is not checked (counted as skipped).
  std::size_t queue_capacity = 64;
  // How much lower than the caller's its threads' CPU priority is (nice
  // increment, 0..19; util/thread_priority.h): with fewer free cores than
  // busy threads the tracker then gets a core first (see LocalMapperOptions).
  int thread_nice = 10;

  void Check() const;  // throws dlslam::Error with the values
};

struct LoopEvent {
  KeyFrameId current = kNoId;
  KeyFrameId loop = kNoId;
  double current_timestamp = 0.0;
  double loop_timestamp = 0.0;
  int inliers = 0;
  LoopCorrection correction;
};

struct LoopClosingStats {
  int keyframes_checked = 0;
  int keyframes_skipped = 0;  // queue full
  int consistent_candidates = 0;  // reached geometric verification
  int loops_rejected = 0;         // keyframes whose consistent candidates all failed it
  int loops_closed = 0;
  int global_bundles_completed = 0;
  int global_bundles_aborted = 0;  // by a newer loop, or a map merged meanwhile
  std::vector<LoopEvent> loops;
};

class LoopCloser {
 public:
  // `map`, `index` and `mapper` outlive the closer; `timings` (optional) too.
  LoopCloser(const LoopClosingOptions& options, Map* map, const place::KeyFrameIndex* index, LocalMapper* mapper,
             StageTimings* timings = nullptr);
  ~LoopCloser();
  LoopCloser(const LoopCloser&) = delete;
  LoopCloser& operator=(const LoopCloser&) = delete;

  // Starts the thread. Without it, Enqueue works inline.
  void Start();
  // A keyframe local mapping has finished. Never blocks on a full queue.
  void Enqueue(KeyFrameId keyframe);
  // Checks the queued keyframes, waits for a running bundle adjustment, joins.
  void Stop();

  LoopClosingStats stats() const;

 private:
  void Run();
  // Process, with a failure logged instead of thrown (in either mode).
  void ProcessGuarded(KeyFrameId keyframe);
  void Process(KeyFrameId keyframe);
  // Aborts and joins a running global bundle adjustment.
  void AbortGlobalBundle();
  void RunGlobalBundle();

  LoopClosingOptions options_;
  Map* map_;
  LocalMapper* mapper_;
  StageTimings* timings_;
  LoopDetector detector_;  // used by the loop thread only
  BoundedQueue<KeyFrameId> queue_;
  std::thread thread_;
  std::thread bundle_thread_;
  std::atomic<bool> abort_bundle_{false};
  mutable std::mutex stats_mutex_;
  LoopClosingStats stats_;
};

}  // namespace dlslam

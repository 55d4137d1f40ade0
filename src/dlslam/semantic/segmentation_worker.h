#pragma once
// The semantic thread: segments frames in its own thread, in the order they
// are submitted, so that the tracker can extract ORB features meanwhile and
// wait only for what is left (the paper's Fig. 1):
//
//   SegmentationWorker worker(MakeSegmenter(options));
//   auto mask = worker.Submit(frame.color);       // returns at once (blocks only when the queue is full)
//   ... extract ORB features ...
//   const SegmentationResult& r = mask.get();     // waits for the segmentation if still running
//
// At a lower rate (segment_every = k), only every k-th submitted frame is
// segmented; the frames in between get the last segmented frame's masks with
// the dynamic mask dilated by propagation_grow_px per frame of distance.

#include <atomic>
#include <cstddef>
#include <future>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <thread>

#include "dlslam/semantic/segmenter.h"
#include "dlslam/util/bounded_queue.h"

namespace dlslam::semantic {

struct SegmentationWorkerOptions {
  // Frames waiting to be segmented [frames]; Submit blocks while it is full.
  std::size_t queue_capacity = 2;
  // Segment every k-th submitted frame (1 = all) [frames].
  int segment_every = 1;
  // Extra dilation of a propagated dynamic mask per frame since the segmented
  // one [px / frame], for the motion in between (4: keeps the recall of
  // segmenting every frame at k = 2, 3 on DAVIS parkour, docs/semantic.md).
  int propagation_grow_px = 4;
  // How much lower than the caller's the thread's CPU priority is (nice
  // increment, 0..19; util/thread_priority.h): with fewer free cores than
  // busy threads the tracker then gets a core first. 0: a frame that waits
  // for its own masks waits longer behind a lower-priority network (Bonn
  // full, asynchronous masks, nice 5 / 10: frame p95 57-66 vs 48-55 ms).
  int thread_nice = 0;

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

class SegmentationWorker {
 public:
  // Starts the thread. Throws dlslam::Error for bad options or a null segmenter.
  explicit SegmentationWorker(std::unique_ptr<Segmenter> segmenter, const SegmentationWorkerOptions& options = {});
  ~SegmentationWorker();  // Stop()
  SegmentationWorker(const SegmentationWorker&) = delete;
  SegmentationWorker& operator=(const SegmentationWorker&) = delete;

  // Queues a CV_8UC3 frame (the worker keeps a reference: do not write into
  // it afterwards). The future holds the result, or the frame's error
  // (dlslam::Error from the segmenter, a size change in propagation, or
  // "stopped" when Stop() came first). Throws dlslam::Error after Stop().
  // Call from one thread (the tracker): the frame order is the call order.
  // `publish_as` >= 0: the result is also published for Latest() under that id.
  std::shared_future<SegmentationResult> Submit(cv::Mat bgr, long publish_as = -1);

  // Never blocks: queues the frame for segmentation when no other frame
  // waits (the network is free or finishing one), else returns nullopt and
  // the frame is skipped (the network is behind: no latency added). A larger
  // queue leaves room for Submit's frames (keyframes that must have their
  // own masks) beside at most one of these. The result is published for
  // Latest() under `frame_id`, and returned to whoever wants this frame's
  // own masks after all. Throws dlslam::Error after Stop().
  std::optional<std::shared_future<SegmentationResult>> TrySubmit(cv::Mat bgr, long frame_id);

  struct Published {
    long frame_id = -1;
    SegmentationResult result;  // owns its pixels
  };
  // The newest segmentation finished from TrySubmit (or Submit with
  // `publish_as`, or Publish), a deep copy; nullopt before the first. Any thread.
  std::optional<Published> Latest() const;
  // Publishes a result the caller got from Submit for Latest() under
  // `frame_id` (a frame submitted before its id was known), unless a newer
  // frame's result is published already. Any thread.
  void Publish(long frame_id, const SegmentationResult& result);

  // Finishes the frame being segmented, fails the queued ones (their futures
  // throw "stopped") and joins the thread. Idempotent.
  void Stop();

  // True once Stop() has begun.
  bool stopped() const { return stopping_.load(); }
  const SegmentationWorkerOptions& options() const { return options_; }

 private:
  struct Job {
    cv::Mat bgr;
    std::promise<SegmentationResult> promise;
    long index = 0;        // submission number
    bool segment = true;   // false: propagate the last segmented frame's masks
    long publish_as = -1;  // >= 0: TrySubmit's frame id, published for Latest()
  };

  void Run();
  SegmentationResult Process(const Job& job);

  std::unique_ptr<Segmenter> segmenter_;
  SegmentationWorkerOptions options_;
  BoundedQueue<Job> queue_;
  std::atomic<bool> stopping_{false};
  std::mutex stop_mutex_;
  long submitted_ = 0;  // Submit's thread only
  // Worker thread only: the last successfully segmented frame and its number.
  std::optional<SegmentationResult> last_;
  long last_index_ = -1;
  mutable std::mutex published_mutex_;
  std::optional<Published> published_;  // under published_mutex_
  std::thread thread_;
};

}  // namespace dlslam::semantic

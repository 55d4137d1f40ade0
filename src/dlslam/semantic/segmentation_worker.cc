#include "dlslam/semantic/segmentation_worker.h"

#include <exception>
#include <utility>

#include "dlslam/semantic/label_maps.h"
#include "dlslam/util/check.h"
#include "dlslam/util/thread_priority.h"

namespace dlslam::semantic {

void SegmentationWorkerOptions::Check() const {
  DLSLAM_CHECK(queue_capacity >= 1 && queue_capacity <= 1000, "queue capacity {} [frames] must be in 1..1000",
               queue_capacity);
  DLSLAM_CHECK(segment_every >= 1 && segment_every <= 1000, "segment_every {} [frames] must be in 1..1000",
               segment_every);
  DLSLAM_CHECK(propagation_grow_px >= 0 && propagation_grow_px <= 100,
               "propagation growth {} [px per frame] must be in 0..100", propagation_grow_px);
  DLSLAM_CHECK(thread_nice >= 0 && thread_nice <= 19, "thread_nice {} must be in 0..19", thread_nice);
}

SegmentationWorker::SegmentationWorker(std::unique_ptr<Segmenter> segmenter,
                                       const SegmentationWorkerOptions& options)
    : segmenter_(std::move(segmenter)), options_(options), queue_((options.Check(), options.queue_capacity)) {
  DLSLAM_CHECK(segmenter_ != nullptr, "the segmentation worker needs a segmenter");
  thread_ = std::thread([this] { Run(); });
}

SegmentationWorker::~SegmentationWorker() { Stop(); }

std::shared_future<SegmentationResult> SegmentationWorker::Submit(cv::Mat bgr, long publish_as) {
  DLSLAM_CHECK(!stopping_.load(), "segmentation worker is stopped; no more frames are accepted");
  Job job;
  job.bgr = std::move(bgr);
  job.index = submitted_;
  job.segment = submitted_ % options_.segment_every == 0;
  job.publish_as = publish_as;
  std::shared_future<SegmentationResult> future = job.promise.get_future().share();
  if (!queue_.Push(std::move(job))) {
    throw Error("segmentation worker stopped while the frame was being submitted");
  }
  ++submitted_;
  return future;
}

std::optional<std::shared_future<SegmentationResult>> SegmentationWorker::TrySubmit(cv::Mat bgr, long frame_id) {
  DLSLAM_CHECK(!stopping_.load(), "segmentation worker is stopped; no more frames are accepted");
  Job job;
  job.bgr = std::move(bgr);
  job.index = submitted_;
  job.segment = true;  // a skipped frame is simply not segmented
  job.publish_as = frame_id;
  std::shared_future<SegmentationResult> future = job.promise.get_future().share();
  // Only this thread pushes, so a queue seen empty stays free for the push.
  if (queue_.size() > 0 || !queue_.TryPush(std::move(job))) return std::nullopt;
  ++submitted_;
  return future;
}

std::optional<SegmentationWorker::Published> SegmentationWorker::Latest() const {
  std::lock_guard lock(published_mutex_);
  if (!published_) return std::nullopt;
  return Published{published_->frame_id, DeepCopy(published_->result)};
}

void SegmentationWorker::Publish(long frame_id, const SegmentationResult& result) {
  std::lock_guard lock(published_mutex_);
  if (published_ && published_->frame_id >= frame_id) return;
  published_ = Published{frame_id, DeepCopy(result)};
}

void SegmentationWorker::Stop() {
  std::lock_guard lock(stop_mutex_);
  stopping_.store(true);
  queue_.Stop();
  if (thread_.joinable()) thread_.join();
}

SegmentationResult SegmentationWorker::Process(const Job& job) {
  if (job.segment || !last_) {
    // A frame meant for propagation whose segmented predecessor failed is
    // segmented itself rather than given an older frame's mask.
    last_.reset();
    SegmentationResult result = segmenter_->Segment(job.bgr);
    // The worker's reference copy and every result it hands out own their
    // pixels: a shared cv::Mat buffer would be freed by whichever thread lets
    // go last, synchronised only by OpenCV's reference count (atomics inside
    // a library ThreadSanitizer cannot see, so it reports a race).
    last_ = DeepCopy(result);
    last_index_ = job.index;
    return result;
  }
  DLSLAM_CHECK(job.bgr.size() == last_->labels.size(),
               "frame {} is {}x{} but the segmented frame {} was {}x{}: cannot propagate its mask", job.index,
               job.bgr.cols, job.bgr.rows, last_index_, last_->labels.cols, last_->labels.rows);
  return PropagateResult(*last_, static_cast<int>(job.index - last_index_), options_.propagation_grow_px);
}

void SegmentationWorker::Run() {
  LowerBackgroundPriority(options_.thread_nice, "segmentation");
  while (std::optional<Job> job = queue_.Pop()) {
    if (stopping_.load()) {
      job->promise.set_exception(
          std::make_exception_ptr(Error("segmentation worker stopped before this frame was segmented")));
      continue;
    }
    try {
      SegmentationResult result = Process(*job);
      if (job->publish_as >= 0) Publish(job->publish_as, result);
      job->promise.set_value(std::move(result));
    } catch (...) {
      job->promise.set_exception(std::current_exception());
    }
  }
}

}  // namespace dlslam::semantic

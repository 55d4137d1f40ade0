#include "dlslam/system/semantic_feed.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <utility>

#include "dlslam/util/check.h"

namespace dlslam {

namespace {

// Frames whose depth and pose are kept to carry an older mask to the current
// frame (asynchronous masks are at most a few frames old).
constexpr std::size_t kRecentFrames = 64;

// The network's image of a frame: BGR, and a copy of it when the worker
// may read it after the caller has reused the image.
cv::Mat NetworkImage(const cv::Mat& colour, bool copy) {
  cv::Mat bgr;
  if (colour.type() == CV_8UC1) {
    cv::cvtColor(colour, bgr, cv::COLOR_GRAY2BGR);
  } else {
    bgr = copy ? colour.clone() : colour;
  }
  return bgr;
}

}  // namespace

semantic::SegmenterOptions SystemSegmenterOptions() {
  semantic::SegmenterOptions options;
  options.threads = 1;
  return options;
}

void SemanticThreadOptions::Check() const {
  segmenter.Check();
  worker.Check();
  DLSLAM_CHECK(carry_grow_px >= 0 && carry_grow_px <= max_carry_grow_px && max_carry_grow_px <= 1000,
               "SemanticThreadOptions: carry growth {} px per frame, at most {} px: need 0 <= growth <= max <= 1000",
               carry_grow_px, max_carry_grow_px);
  DLSLAM_CHECK(wait_when_removed_share > 0 && wait_when_removed_share <= 1,
               "SemanticThreadOptions::wait_when_removed_share {} outside (0, 1]", wait_when_removed_share);
  DLSLAM_CHECK(carried_segment_every >= 1 && carried_segment_every <= 1000,
               "SemanticThreadOptions::carried_segment_every {} outside [1, 1000]", carried_segment_every);
  DLSLAM_CHECK(keyframe_mask_max_wait_frames >= 0 && keyframe_mask_max_wait_frames <= 100,
               "SemanticThreadOptions::keyframe_mask_max_wait_frames {} outside [0, 100]",
               keyframe_mask_max_wait_frames);
}

SemanticFeed::SemanticFeed(const SemanticThreadOptions& options, const CameraIntrinsics& camera,
                           StageTimings* timings, std::function<std::optional<SE3d>()> predicted_cam_from_world,
                           std::unique_ptr<semantic::Segmenter> segmenter)
    : options_(options), timings_(timings), predicted_cam_from_world_(std::move(predicted_cam_from_world)) {
  options_.Check();
  DLSLAM_CHECK(timings_ != nullptr);
  semantic::SegmentationWorkerOptions worker = options_.worker;
  // Asynchronous: one skippable frame waiting at most (TrySubmit), so that
  // the newest mask is at most one network run older than the frame being
  // segmented, and room for a held keyframe's frame beside it.
  if (!options_.wait_for_masks) worker.queue_capacity = 2;
  if (!segmenter) segmenter = semantic::MakeSegmenter(options_.segmenter);
  worker_ = std::make_unique<semantic::SegmentationWorker>(std::move(segmenter), worker);
  if (!options_.wait_for_masks) warper_ = std::make_unique<dynamic::MaskWarper>(camera);
}

SemanticFeed::FrameMasks SemanticFeed::ForFrame(long frame_id, const cv::Mat& colour, const cv::Mat& depth,
                                                double timestamp, bool carry) {
  DLSLAM_CHECK(!carry || asynchronous(), "masks are carried only when asynchronous");
  FrameMasks out;
  // Asynchronous, the worker may read the frame after the caller returns: it gets a copy.
  out.image = NetworkImage(colour, /*copy=*/asynchronous());
  if (asynchronous()) {
    recent_.push_back({frame_id, depth.empty() ? cv::Mat() : depth.clone(), std::nullopt});
    if (recent_.size() > kRecentFrames) recent_.pop_front();
  }
  // Frames segmented ahead but never tracked are dropped; one segmented
  // ahead gets its own masks even where carried ones would do.
  while (!ahead_.empty() && ahead_.front().timestamp < timestamp) ahead_.pop_front();
  const bool ahead = !ahead_.empty() && ahead_.front().timestamp == timestamp;
  if (carry && !ahead) {
    if (frame_id - last_segmented_ >= options_.carried_segment_every) {
      out.own = worker_->TrySubmit(out.image, frame_id);  // a busy network skips the frame
      if (out.own) last_segmented_ = frame_id;
    }
    out.carried = true;
    out.prior = [this, frame_id] { return CarriedMasks(frame_id); };
    return out;
  }
  Masks pending;
  if (ahead) {
    pending = ahead_.front().masks;  // segmented while the last frame was tracked
    ahead_.pop_front();
    out.segmented_ahead = true;
  } else {
    pending = worker_->Submit(out.image, asynchronous() ? frame_id : -1);
  }
  last_segmented_ = frame_id;
  // Asynchronous: this frame waits (crowded) and so will the next, mostly.
  // Not when it only had masks ahead: that would chain every later frame.
  if (asynchronous() && !carry && next_ && next_->timestamp > timestamp && ahead_.empty()) {
    ahead_.push_back({next_->timestamp, worker_->Submit(NetworkImage(next_->image, /*copy=*/true))});
  }
  next_.reset();
  // Asynchronous: segmented ahead before its id was known, published for
  // carrying once got (Submit published the others).
  const bool publish = asynchronous() && out.segmented_ahead;
  out.prior = [this, pending, frame_id, publish] {
    const semantic::SegmentationResult& masks = pending.get();
    timings_->Add("semantic", masks.seconds * 1e3);
    if (publish) worker_->Publish(frame_id, masks);
    // Asynchronous, published under frame_id: not timed again when later frames carry it.
    last_timed_mask_ = std::max(last_timed_mask_, frame_id);
    return dynamic::SemanticMasks{masks.dynamic_mask, masks.movable_mask};
  };
  return out;
}

void SemanticFeed::SetPose(long frame_id, const std::optional<SE3d>& cam_from_world) {
  if (!recent_.empty() && recent_.back().id == frame_id) recent_.back().cam_from_world = cam_from_world;
}

SemanticFeed::Masks SemanticFeed::Segment(const cv::Mat& image, long frame_id) {
  last_segmented_ = frame_id;
  return worker_->Submit(image, frame_id);
}

void SemanticFeed::SegmentAhead(const cv::Mat& colour, double timestamp) {
  if (asynchronous()) {
    // Not copied unless segmented: the caller keeps it unchanged until it is tracked.
    if (!next_ || timestamp > next_->timestamp) next_ = NextFrame{timestamp, colour};
    return;
  }
  constexpr std::size_t kMaxAhead = 2;  // the frame being tracked and the next
  if (ahead_.size() >= kMaxAhead) return;
  if (!ahead_.empty() && timestamp <= ahead_.back().timestamp) return;  // not in frame order
  // A copy: the caller's image may be reused before the worker reads it.
  ahead_.push_back({timestamp, worker_->Submit(NetworkImage(colour, /*copy=*/true))});
}

void SemanticFeed::Stop() { worker_->Stop(); }

dynamic::SemanticMasks SemanticFeed::CarriedMasks(long frame_id) {
  const Stopwatch watch;
  const std::optional<semantic::SegmentationWorker::Published> latest = worker_->Latest();
  if (!latest) return {};  // nothing segmented yet: geometry alone
  const semantic::SegmentationResult& masks = latest->result;
  const long age = frame_id - latest->frame_id;
  if (latest->frame_id > last_timed_mask_) {  // the network's time, once per segmented frame
    timings_->Add("semantic", masks.seconds * 1e3);
    last_timed_mask_ = latest->frame_id;
  }
  timings_->Add("semantic_age_frames", static_cast<double>(age));
  if (age <= 0) return {masks.dynamic_mask, masks.movable_mask};
  // Frame s's depth and pose, and the prediction of this frame's.
  const RecentFrame* source = nullptr;
  for (const RecentFrame& r : recent_) {
    if (r.id == latest->frame_id) source = &r;
  }
  const std::optional<SE3d> predicted = predicted_cam_from_world_();
  SE3d t_from_s;  // identity when a pose is missing: the masks stay, grown
  if (source && source->cam_from_world && predicted) t_from_s = *predicted * source->cam_from_world->Inverse();
  const cv::Mat depth = source ? source->depth : cv::Mat();
  const int grow = std::min(options_.max_carry_grow_px, options_.carry_grow_px * static_cast<int>(age));
  dynamic::SemanticMasks carried;
  carried.dynamic = warper_->Warp(masks.dynamic_mask, depth, t_from_s, grow);
  if (!masks.movable_mask.empty() && cv::countNonZero(masks.movable_mask) > 0) {
    carried.movable = warper_->Warp(masks.movable_mask, depth, t_from_s, grow);
  }
  timings_->Add("semantic_carry", watch.ElapsedMs());
  return carried;
}

}  // namespace dlslam

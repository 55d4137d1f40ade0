#pragma once
// The semantic thread's side of SlamSystem: which frames the network
// segments, and which masks each frame's dynamic stage gets: its own
// (segmented in turn, or ahead while the last frame was tracked; waited for
// after ORB extraction) or, with asynchronous masks, the newest finished
// ones carried to it with the predicted camera motion and the depth of the
// frame they were made on. Tracking thread only.
//
//   SemanticFeed feed(options.semantic, camera, &timings, [&] { return tracker.PredictedCamFromWorld(); });
//   feed.SegmentAhead(next_colour, next_t);                    // optional
//   SemanticFeed::FrameMasks m = feed.ForFrame(id, colour, depth, t, /*carry=*/false);
//   ... dynamic stage calls m.prior() ...
//   feed.SetPose(id, tracked_pose);                            // asynchronous: for carrying

#include <opencv2/core.hpp>

#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>

#include "dlslam/data/camera.h"
#include "dlslam/dynamic/mask_fusion.h"
#include "dlslam/dynamic/mask_warp.h"
#include "dlslam/geometry/se3.h"
#include "dlslam/semantic/segmentation_worker.h"
#include "dlslam/util/timing.h"

namespace dlslam {

// The network's options in the system: inference on one OpenCV thread.
// OpenCV's thread count is process-wide, and the system's own threads
// (tracking, network, local mapping, frame reading) already fill a small
// machine: OpenCV's pool on top of them only spins (real Bonn crowd, 2
// cores, full mode with asynchronous masks: 17.2 s of CPU instead of 22.2 s,
// 11.3 s wall instead of 13.2 s; waiting for masks: 13.8 s wall either way).
semantic::SegmenterOptions SystemSegmenterOptions();

// The semantic thread of modes semantic and full.
struct SemanticThreadOptions {
  // Segment every frame that comes without a prior of its own
  // (DynamicInputs::semantic_prior empty) with the network, in the system's
  // worker thread. false: the caller always gives the prior (ground-truth
  // masks, a folder of masks, its own network); no model is loaded.
  bool network = true;
  // The network: model file ("" = the shipped one), input size, classes,
  // mask margin, OpenCV threads (SystemSegmenterOptions).
  semantic::SegmenterOptions segmenter = SystemSegmenterOptions();
  // The worker: queue length, rate (segment every k-th frame, propagating
  // the masks to the frames between).
  semantic::SegmentationWorkerOptions worker;
  // true: each frame waits for its own masks (after ORB extraction). false
  // (asynchronous, experimental): the tracker never waits; a frame is
  // segmented only when the network is free, and each frame uses the newest
  // finished masks carried to it with the predicted camera motion and that
  // frame's depth (dynamic::MaskWarper), grown by carry_grow_px per frame of
  // age; geometry covers what moved in between. segment_every is unused.
  bool wait_for_masks = true;
  int carry_grow_px = 8;       // [px / frame of age]
  int max_carry_grow_px = 24;  // [px]
  // Asynchronous only: a frame waits for its own masks after one whose
  // dynamic stage removed at least this share of the image, or while
  // tracking is not ok. In a crowd a carried mask is too stale (people walk
  // 10-20 px a frame) and the few static keypoints left are outnumbered by
  // the people's edges (Bonn crowd: ATE 0.022-0.14 m carrying always,
  // 0.016-0.058 m waiting after frames that lost 75 % of their keypoints,
  // 0.016-0.027 m at 60 %, where most frames wait). 75 % of the keypoints
  // were 42-62 % of the pixels on those frames (people hold more than their
  // share of keypoints); the share is now taken in pixels, which does not
  // depend on what the extractor found. In pixels (2026-12-03, 5-6 runs
  // each): 0.55 gave 1.28-1.35x real time, 0.0142-0.0190 m; 0.65
  // 1.47-1.57x, 0.0152-0.0176 m; 0.8 1.69-1.74x but 0.020 and 0.063 m.
  // (0, 1]; 1 = only when everything was removed.
  double wait_when_removed_share = 0.65;
  // Asynchronous only: a keyframe made from a frame with carried masks is
  // held back from the map until that frame's own masks arrive (it is
  // segmented, unless it was already), and only its keypoints outside them
  // enter the map; tracking goes on meanwhile. After
  // keyframe_mask_max_wait_frames further frames the tracker waits for them
  // [frames; the network takes about one frame's time, and may be finishing
  // another].
  bool keyframes_wait_for_own_masks = true;
  int keyframe_mask_max_wait_frames = 3;
  // Asynchronous only: a frame with carried masks is offered to the network
  // only when at least this many frames passed since the last frame handed
  // to it (waiting frames and held keyframes count) [frames]; 1 = whenever
  // the network is free.
  int carried_segment_every = 1;

  void Check() const;
};

class SemanticFeed {
 public:
  using Masks = std::shared_future<semantic::SegmentationResult>;

  // Loads the model (options.segmenter) now: a missing or broken file is an
  // InputError here, not on the first frame. `predicted_cam_from_world`:
  // the tracker's prediction of the frame being tracked (carrying needs it).
  // `segmenter`: null for the network of options.segmenter (tests pass a stand-in).
  SemanticFeed(const SemanticThreadOptions& options, const CameraIntrinsics& camera, StageTimings* timings,
               std::function<std::optional<SE3d>()> predicted_cam_from_world,
               std::unique_ptr<semantic::Segmenter> segmenter = nullptr);

  // Asynchronous masks (!options.wait_for_masks).
  bool asynchronous() const { return warper_ != nullptr; }

  struct FrameMasks {
    // The masks for the dynamic stage, blocking (own masks) or not (carried).
    std::function<dynamic::SemanticMasks()> prior;
    bool carried = false;          // an earlier frame's masks, carried to this one
    bool segmented_ahead = false;  // its own masks, started by SegmentAhead
    std::optional<Masks> own;      // carried: its own masks, when the network took it too
    cv::Mat image;                 // what the network sees of the frame (a held keyframe's)
  };
  // The frame `frame_id` (increasing). `carry`: asynchronous, and the view
  // lets a carried mask do (SlamSystem: not crowded, tracking ok); the
  // network then takes the frame only when it is free. Otherwise the frame
  // gets its own masks (those segmented ahead for this timestamp, if any).
  FrameMasks ForFrame(long frame_id, const cv::Mat& colour, const cv::Mat& depth, double timestamp, bool carry);
  // The tracked pose of `frame_id` (asynchronous: a mask made on it is
  // carried from there).
  void SetPose(long frame_id, const std::optional<SE3d>& cam_from_world);
  // Segments a frame's image (FrameMasks::image) now, e.g. for a held keyframe.
  Masks Segment(const cv::Mat& image, long frame_id);
  // SlamSystem::SegmentAhead, in frame order; the colour image is checked
  // by the caller. Waiting for masks: segmented now, at most two frames
  // ahead. Asynchronous: kept, and segmented by the next ForFrame that gets
  // its own masks (a crowd, tracking not ok), since the frame after such a
  // frame mostly needs its own too: it then waits only for what is left of
  // a run started a frame earlier, not for a whole run behind another.
  void SegmentAhead(const cv::Mat& colour, double timestamp);
  void Stop();

 private:
  dynamic::SemanticMasks CarriedMasks(long frame_id);

  SemanticThreadOptions options_;
  StageTimings* timings_;
  std::function<std::optional<SE3d>()> predicted_cam_from_world_;
  std::unique_ptr<semantic::SegmentationWorker> worker_;
  std::unique_ptr<dynamic::MaskWarper> warper_;  // asynchronous only
  // Asynchronous: the recent frames' depth and pose, to carry a finished
  // mask to the current frame.
  struct RecentFrame {
    long id = 0;
    cv::Mat depth;
    std::optional<SE3d> cam_from_world;
  };
  std::deque<RecentFrame> recent_;
  // SegmentAhead's frames, oldest first.
  struct AheadFrame {
    double timestamp = 0.0;
    Masks masks;
  };
  std::deque<AheadFrame> ahead_;
  // Asynchronous: the frame after the one being tracked, not segmented yet.
  struct NextFrame {
    double timestamp = 0.0;
    cv::Mat image;  // the caller's colour image (unchanged until tracked)
  };
  std::optional<NextFrame> next_;
  long last_timed_mask_ = -1;  // the newest segmented frame timed as "semantic" (once, carried or own)
  long last_segmented_ = -1000000;  // the newest frame handed to the network
};

}  // namespace dlslam

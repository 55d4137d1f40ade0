#pragma once
// The per-frame dynamic-object stage of SlamSystem, between ORB extraction
// and tracking: waits for the semantic prior, tests the frame's depth against
// earlier keyframes (multi-view geometry with the tracker's first pose
// estimate), fuses both into one removal mask (SlamSystem gives tracking the
// frame without its keypoints), and culls map points that moved away. Runs
// on the tracking thread; it reads the map through copies and writes to it
// only through Map's locked calls, so the local-mapping thread may run
// alongside.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map.h"
#include "dlslam/system/dynamic_options.h"
#include "dlslam/tracking/tracker.h"
#include "dlslam/util/timing.h"

namespace dlslam {

// What the caller adds to a frame for the dynamic stage.
struct DynamicInputs {
  // The segmentation of the frame (dynamic::SemanticMasks: a-priori dynamic
  // classes such as people, and movable ones such as chairs; CV_8UC1 at the
  // colour image's size), deferred: called once per frame, by
  // DynamicStage::TakePrior (before ORB extraction, which then leaves the
  // removed regions out), only in modes semantic and full. It may block until a
  // segmentation thread has the masks (the wait is timed as stage
  // "semantic_wait"). Empty function or empty masks: no prior for this frame.
  std::function<dynamic::SemanticMasks()> semantic_prior;
  // Ground truth for statistics only (CV_8UC1, non-zero = moving); empty =
  // none. Never used to decide anything.
  cv::Mat moving_truth;
};

// Totals over a run.
struct DynamicStats {
  DynamicMode mode = DynamicMode::kOrb;
  dynamic::SearchKind search = dynamic::SearchKind::kAntColony;
  dynamic::FusionPolicy fusion = dynamic::FusionPolicy::kUnion;  // as configured (used in mode full)
  std::int64_t keypoints_total = 0;   // keypoints extracted, in every frame
  std::int64_t keypoints_tested = 0;   // projected reference points tested by geometry
  std::int64_t keypoints_dynamic = 0;  // of those, found moving
  std::int64_t keypoints_removed = 0;  // frame keypoints ignored (prior, geometry or both)
  // Pixels in the removal masks and in the frames: what was removed even
  // where the extractor left the prior's pixels out (no keypoint to count).
  std::int64_t pixels_removed = 0;
  std::int64_t pixels_total = 0;
  std::int64_t frames_with_geometry = 0;  // frames the geometric check ran on
  std::int64_t map_points_culled = 0;     // vanished map points removed from the map
  std::int64_t movable_segments_dropped = 0;  // movable-class segments geometry saw move, dropped whole
  // Frames whose check was repeated with the pose of the "moving" region's
  // keypoints, and those where that labelling won (DynamicOptions::resolve_inverted_check).
  std::int64_t inverted_checks_tried = 0;
  std::int64_t inverted_checks_resolved = 0;
  // Mode full: frames whose geometric mask was set aside because it took
  // most of what the prior left (DynamicOptions::max_geometry_share_of_prior_static).
  std::int64_t geometry_overruled = 0;
  // The dense free-space check (GeometryOptions::free_space): frames it ran
  // on, kept views it ignored as misposed, and the image share it found
  // moved in (summed over the frames; divide by free_space_frames).
  std::int64_t free_space_frames = 0;
  std::int64_t free_space_views_ignored = 0;
  double free_space_share_sum = 0.0;
  // Per keypoint of every frame with ground truth: removed and moving (true
  // positive), removed and still (false positive), kept and moving (false negative).
  std::int64_t frames_with_truth = 0;
  std::int64_t true_positives = 0;
  std::int64_t false_positives = 0;
  std::int64_t false_negatives = 0;

  // nullopt without ground truth, or when nothing was removed / nothing moved.
  std::optional<double> precision() const;
  std::optional<double> recall() const;
  // pixels_removed / pixels_total; nullopt before any frame.
  std::optional<double> image_share_removed() const;
};

// Does `fused` (prior and geometry) take more than `max_share` of the frame's
// keypoints that `prior_removal` leaves (empty: no pixel)? Then mode full
// takes geometry's check to have failed (DynamicOptions::max_geometry_share_of_prior_static).
bool GeometryTakesTooMuch(const Frame& frame, const cv::Mat& prior_removal, const cv::Mat& fused, double max_share);

// A frame's semantic prior and what it removes on its own, known before the
// frame's ORB features are extracted.
struct DynamicPrior {
  dynamic::SemanticMasks masks;  // empty: no prior for this frame
  // The prior fused alone (dilated as the fused mask is), CV_8UC1, 255 =
  // removed; empty when it removes no pixel.
  cv::Mat removal;
  // Nothing later gives back a keypoint inside `removal` (fusion policies
  // union and semantic: the fused mask contains it whatever geometry finds),
  // so the extractor may leave those pixels out and spend its budget on the
  // rest. False under geometry_confirms, which keeps segments geometry shows
  // still.
  bool final = false;

  double removed_share() const;  // of the image's pixels, in `removal`
};

// What the dynamic stage removes from a frame.
struct DynamicRemoval {
  cv::Mat mask;                  // CV_8UC1, 255 = removed; empty when nothing is (mode orb)
  std::vector<bool> keypoints;   // per keypoint of the frame: on the mask
  std::size_t count = 0;         // keypoints on the mask
  std::size_t pixels = 0;        // pixels on the mask
  double image_share() const { return mask.empty() ? 0.0 : static_cast<double>(pixels) / static_cast<double>(mask.total()); }
};

// A keyframe's keypoints that have depth, in world coordinates, with the map
// point each holds (kNoId if none): what the geometric check projects.
dynamic::ReferenceView MakeReferenceView(const KeyFrameSnapshot& keyframe);

class DynamicStage {
 public:
  // `map`, `tracker` and `timings` outlive the stage.
  DynamicStage(const DynamicOptions& options, const CameraIntrinsics& camera, Map* map, const Tracker* tracker,
               StageTimings* timings);

  // Waits for the frame's semantic prior (modes semantic and full; timed as
  // "semantic_wait"), completes its dynamic mask with `depth` (CV_32FC1
  // metres; empty: not completed; DynamicOptions::completion) and fuses it
  // alone. Throws dlslam::Error for a prior of the wrong type or size.
  DynamicPrior TakePrior(const DynamicInputs& inputs, const cv::Mat& depth);

  // What to remove from `frame`, whose prior `prior` is: tracking and
  // mapping get the frame without those keypoints (SlamSystem); the mask
  // contains prior.removal when prior.final. `depth`: the frame's CV_32FC1
  // metres (empty: geometry is skipped). `moving_truth`: as
  // DynamicInputs::moving_truth.
  DynamicRemoval Process(const Frame& frame, const cv::Mat& depth, const DynamicPrior& prior,
                         const cv::Mat& moving_truth = {});
  // TakePrior and Process in one, for a frame extracted without its prior.
  DynamicRemoval Process(const Frame& frame, const cv::Mat& depth, const DynamicInputs& inputs);

  // A tracked frame's depth (CV_32FC1 metres) at its pose, for the dense
  // free-space check of the frames after it (GeometryOptions::free_space);
  // SlamSystem offers every tracked frame that was not gated. A map
  // correction (loop closing, a merge) forgets the views offered before it.
  void OfferView(const cv::Mat& depth, const SE3d& cam_from_world);

  const DynamicStats& stats() const { return stats_; }

 private:
  // The fusion policy of the mode.
  dynamic::FusionOptions Fusion() const;
  // The multi-view check with the tracker's first pose estimate; a result
  // with an empty mask when it cannot run (not tracking, no keyframe).
  // `estimate_knows_movers`: the estimate already ignored a semantic prior's
  // keypoints, so the labelling is not checked for inversion.
  dynamic::GeometryResult DetectGeometrically(const Frame& frame, const cv::Mat& depth, bool estimate_knows_movers);
  // Mode full: replaces `fused` (prior and geometry) by the prior's removal
  // alone when GeometryTakesTooMuch; true if it did.
  bool OverruleFailedGeometry(const Frame& frame, const DynamicPrior& prior, cv::Mat* fused);
  // The dense check's violations at `cam_from_world` (empty: none, or no
  // view); `count`: into the stats (the first estimate's, not a retry's).
  cv::Mat MovedIn(const cv::Mat& depth, const SE3d& cam_from_world, bool count);
  void CountAgainstTruth(const Frame& frame, const std::vector<bool>& removed, const cv::Mat& truth);

  DynamicOptions options_;
  CameraIntrinsics camera_;
  Map* map_;
  const Tracker* tracker_;
  StageTimings* timings_;
  dynamic::GeometryDetector detector_;
  dynamic::FreeSpaceCheck free_space_;
  std::uint64_t free_space_generation_ = 0;  // the map generation of its views
  DynamicStats stats_;
};

}  // namespace dlslam

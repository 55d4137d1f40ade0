#pragma once
// The one entry point of the SLAM library: feed RGB-D frames, get poses.
// Owns the feature extractor, the tracker (on the caller's thread), the map,
// the local-mapping thread (or runs mapping inline in sequential mode,
// which is reproducible bit for bit) and, in modes semantic and full, the
// semantic thread: the segmentation network in its own worker.
//
//   SlamSystem slam(camera, options);          // options.dynamic.mode: orb, semantic, geometry, full
//   for (...) slam.TrackRgbd(bgr, depth_m, t); // the network's masks, segmented while ORB runs
//   for (...) slam.TrackRgbd(bgr, depth_m, t, my_masks);   // or priors of your own
//   slam.Shutdown();
//   io::WriteTumTrajectory("traj.txt", slam.CameraTrajectory());

#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "dlslam/data/camera.h"
#include "dlslam/data/trajectory.h"
#include "dlslam/dense/tsdf_volume.h"
#include "dlslam/features/orb_extractor.h"
#include "dlslam/loop/loop_closer.h"
#include "dlslam/map/map.h"
#include "dlslam/mapping/local_mapper.h"
#include "dlslam/place/keyframe_index.h"
#include "dlslam/system/dynamic_stage.h"
#include "dlslam/system/semantic_feed.h"
#include "dlslam/tracking/tracker.h"
#include "dlslam/util/timing.h"

namespace dlslam {

// ORB options for the extraction outside removed regions when they are
// large: what is left in a crowd is mostly weakly textured (walls, desks), so
// FAST starts lower (8 / 4 grey levels instead of 20 / 7; on the real Bonn
// crowd frames the static re-extraction found 107-300 keypoints at 20 / 7 in
// the most crowded frames).
features::OrbOptions StaticOrbOptions();

struct SystemOptions {
  features::OrbOptions orb;
  features::OrbOptions static_orb = StaticOrbOptions();
  TrackerOptions tracker;
  LocalMapperOptions mapping;
  DynamicOptions dynamic;
  SemanticThreadOptions semantic;
  // When the dynamic stage removes at least this share of a frame's
  // keypoints, its ORB features are extracted again outside the removed
  // regions, so that tracking gets the whole keypoint budget on static
  // structure (ORB keypoints gather on texture: in a crowd 90 % of the
  // first extraction lies on people, leaving too few to track). (0, 1];
  // 1 = only when every keypoint was removed. Costs one more extraction on
  // such frames (~3 ms).
  double reextract_removed_share = 0.1;
  // What the semantic prior removes whatever geometry finds (fusion union
  // or semantic; DynamicPrior::final) is left out of the frame's one ORB
  // extraction, which then spends its whole budget on the rest: the prior is
  // waited for before extraction, and only what geometry adds can still call
  // for a re-extraction. False: extract the whole frame, then re-extract
  // (one more extraction, 3-5 ms, on nearly every frame of a crowd).
  bool extract_outside_prior = true;
  // The extraction outside the prior uses static_orb's FAST thresholds when
  // the prior removes at least this share of the image, else orb's [0, 1]
  // (keypoints gather on people: 5 % of the pixels hold about 10 % of the
  // keypoints, reextract_removed_share's share).
  double static_orb_removed_share = 0.05;
  // Run local mapping inline after each keyframe instead of in its thread.
  bool sequential = false;
  // Threaded: a frame waits until local mapping has finished the keyframes
  // made this many frames or more before it (0 = never), for at most
  // max_mapping_wait_ms and only for time the camera would have left it: as
  // long as frames are tracked faster than their timestamps go. A mapper
  // left behind leaves tracking on points and poses its bundle adjustment
  // has not refined yet, for frames on end: run faster than the camera on 2
  // cores, tracking and the network starve it (Bonn full, 10 interleaved
  // runs each: local mapping 55 ms a keyframe wall, ATE 0.0130-0.0160 m,
  // median 0.0150, without the wait; 35 ms and 0.0127-0.0142 m, median
  // 0.0133, waiting up to 15 ms for the keyframe of the frame before;
  // real-time factor 2.20 -> 2.04x, frame p95 21 -> 28 ms, median
  // unchanged; sequential: 0.0125 m). Waiting only for its new points
  // (before the bundle adjustment) gave nothing (0.0143 m). Live at 30 Hz
  // (--realtime) the tracker idles between frames and this never waits.
  int max_mapping_lag_frames = 1;
  int max_mapping_wait_ms = 15;
  // Relocalize a lost camera against the map by bag of words (loads the
  // vocabulary once, ~5 ms, and describes every keyframe, ~1 ms each).
  bool relocalization = true;
  // Close loops (bag-of-words detection, pose graph, global bundle
  // adjustment in the background); shares the vocabulary.
  bool loop_closing = true;
  LoopClosingOptions loop;
  // While tracking in a new map (TrackerOptions::new_map_after_lost_frames),
  // every k-th frame tries to relocalize in the older maps to merge it
  // (~2-10 ms per try) [frames, >= 1].
  int merge_every_frames = 3;
  // Two successive tries must put the new map at the same place, within
  // these, for it to be merged [m, deg]: single relocalizations in a
  // repetitive room were off by 0.2-0.6 m with 50-90 inliers.
  double merge_agreement_m = 0.05;
  double merge_agreement_deg = 3.0;
  // Track against the map without ever adding keyframes (a loaded map,
  // LoadMap; `dlslam run --localize`).
  bool localization_only = false;
  // Vocabulary file (.dlv); "" = the shipped one (place::FindVocabulary).
  std::string vocabulary;
  // Keep every keyframe's colour, depth and removed dynamic regions for the
  // dense map (FuseDenseMap): ~1.8 MB per 640x480 keyframe while it lives
  // (culled keyframes are dropped).
  bool keep_keyframe_images = false;

  void Check() const;
};

// How a frame's pose was obtained.
//   tracked      matched to the map (the normal case)
//   relocalized  found again in the map after being lost
//   coasted      the motion model's, through a short loss of tracking
//                (people covering the view): not confirmed by the map
//   new_map      tracked in a map started after a loss that relocalization
//                could not end, before that map was merged into the older
//                one (after a merge its poses are in the older map's frame;
//                if it never merges they continue from the last pose seen)
//   none         no pose: lost, unreadable, or before initialisation
enum class PoseSource { kTracked, kRelocalized, kCoasted, kNewMap, kNone };
const char* ToString(PoseSource source);

struct FramePoseSource {
  double timestamp = 0.0;
  PoseSource source = PoseSource::kNone;
};

struct RunStats {
  int frames = 0;           // frames given to the system (read or not)
  int frames_tracked = 0;   // with a pose confirmed by the map (tracked or relocalized)
  int frames_coasted = 0;   // with the motion model's pose (PoseSource::kCoasted)
  int frames_new_map = 0;   // of frames_tracked, tracked in a new map before it merged (PoseSource::kNewMap)
  int maps_started = 0;     // new maps started after a loss (TrackerOptions::new_map_after_lost_frames)
  int maps_merged = 0;      // of those, merged into an older map
  int frames_lost = 0;      // not tracked after initialisation, or unreadable
  int frames_waiting = 0;   // before initialisation
  int frames_dropped = 0;   // live playback: overwritten by the next frame before the system was free (MarkDropped)
  int frames_extracted_outside_prior = 0;  // ORB extraction left the prior's removal out (extract_outside_prior)
  int frames_reextracted = 0;  // ORB features extracted again outside the removed regions
  int relocalizations = 0;  // lost -> tracked again through relocalization
  int jumps_refused = 0;    // tracked poses refused as too far from the motion model (coasted instead)
  int frames_gated = 0;     // tracked poses solved again on the matches near the prediction (TrackerOptions::gate_departure_m)
  int frames_segmented_ahead = 0;  // whose masks were started by SegmentAhead
  // Asynchronous masks: keyframes held until their own masks came
  // (SemanticThreadOptions::keyframe_mask_max_wait_frames), those dropped
  // then (the map moved meanwhile, or too few matches outside the masks),
  // and the keypoints their own masks took out.
  int keyframes_held = 0;
  int keyframes_held_dropped = 0;
  std::int64_t keyframe_keypoints_masked_late = 0;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  LocalMappingStats mapping;
  LoopClosingStats loop;
  DynamicStats dynamic;
  std::map<std::string, TimingSummary> timing_ms;  // per stage

  int frames_posed() const { return frames_tracked + frames_coasted; }
  int frames_without_pose() const { return frames_lost + frames_waiting + frames_dropped; }
  // PoseSource::kTracked: tracked, neither relocalized nor in a new map.
  int frames_tracked_source() const { return frames_tracked - relocalizations - frames_new_map; }
};

class SlamSystem {
 public:
  SlamSystem(const CameraIntrinsics& camera, const SystemOptions& options);
  ~SlamSystem();
  SlamSystem(const SlamSystem&) = delete;
  SlamSystem& operator=(const SlamSystem&) = delete;

  // One frame: colour (CV_8UC3 BGR or CV_8UC1), depth (CV_32FC1 metres,
  // registered to colour, 0 = none; may be empty), and what the dynamic
  // stage may use (dynamic_stage.h): the semantic prior, deferred so that a
  // segmentation thread can work while ORB features are extracted (empty:
  // the system's own network, when options.semantic.network), and ground
  // truth for statistics. Keypoints are extracted on the whole image; the
  // mode decides which are then ignored by tracking and mapping.
  TrackingResult TrackRgbd(const cv::Mat& colour, const cv::Mat& depth, double timestamp,
                           const DynamicInputs& dynamic);
  // The same with the semantic prior at hand (CV_8UC1, non-zero = a class
  // that may move; empty = none). Mode orb ignores it.
  TrackingResult TrackRgbd(const cv::Mat& colour, const cv::Mat& depth, double timestamp,
                           const cv::Mat& semantic_prior = cv::Mat());
  // The frame that will be tracked next, when it is already at hand (read
  // ahead from disk, or queued behind the camera while the tracker is
  // busy): the network starts on it now, while the current frame is
  // tracked, instead of after TrackRgbd takes it, so that segmenting every
  // frame costs the tracker little waiting. TrackRgbd with that timestamp
  // then uses these masks (the image must not change meanwhile; other
  // timestamps drop it). Call in frame order, the first frame too; at most
  // two frames are ahead (more are not segmented ahead). Does nothing
  // without the system's network (options.semantic.network). With
  // asynchronous masks the frame is segmented ahead only when the current
  // one waits for its own masks (a crowd, tracking not ok), since the next
  // frame then mostly waits too.
  void SegmentAhead(const cv::Mat& colour, double timestamp);
  // Loads a map saved by SaveMap before the first frame: tracking starts by
  // relocalizing in it; with options.localization_only it is never
  // extended, else mapping goes on on top of it. Throws InputError for a
  // bad file, or a map made with another camera or ORB pyramid.
  void LoadMap(const std::filesystem::path& file);
  // Writes the map (after Shutdown, so that mapping is finished); see
  // map/map_file.h. Throws InputError when the file cannot be written.
  void SaveMap(const std::filesystem::path& file) const;

  // A frame that could not be read counts as lost.
  void MarkLost(double timestamp);
  // A frame a live camera delivered while the system was busy, replaced by
  // the next one before the system was free (io::LivePlayback): no pose;
  // tracking goes on from the next frame with the motion model.
  void MarkDropped(double timestamp);
  // Finishes the semantic thread, local mapping, then loop closing (and a
  // running global bundle adjustment). Called by the destructor too.
  void Shutdown();

  // world_from_cam of every tracked frame, from its reference keyframe's
  // current pose and the relative pose at tracking time (as ORB-SLAM does).
  Trajectory CameraTrajectory() const;
  Trajectory KeyFrameTrajectory() const;
  // The last frame as tracking saw it, for views: its detected keypoints
  // kept for tracking and those the dynamic stage removed (pixels of the
  // colour image), the removal mask (CV_8UC1, empty when nothing was
  // removed) and the part of it the network's prior removed alone (the rest
  // is geometry's; empty when none). Tracking thread only.
  struct FrameView {
    std::vector<cv::Point2f> kept;
    std::vector<cv::Point2f> removed;
    cv::Mat removed_mask;
    cv::Mat prior_mask;
  };
  const FrameView& LastFrameView() const { return last_view_; }
  // Every map point's position (world) now, for views and reports (any thread).
  std::vector<Eigen::Vector3d> MapPointPositions() const;
  // Every frame given to the system, in order, with how its pose was
  // obtained (frames of CameraTrajectory are those with a source other than
  // none, unless their keyframe was culled away).
  const std::vector<FramePoseSource>& FrameSources() const { return sources_; }
  RunStats Stats() const;

  // The dense static model: every kept keyframe's depth fused at its
  // current (optimised) pose, without the regions the dynamic stage removed
  // (needs options.keep_keyframe_images; call after Shutdown for the final
  // poses). `tag(timestamp)`, when given, returns a CV_8UC1 mask per
  // keyframe counted in SurfacePoint::tagged_share (ground-truth people, to
  // measure how much of them got into the model) or an empty one.
  // `leave_out_removed` false fuses the removed regions too (for comparisons).
  dense::TsdfVolume FuseDenseMap(const dense::TsdfOptions& options, const std::function<cv::Mat(double)>& tag = {},
                                 bool leave_out_removed = true) const;

 private:
  struct FrameRecord {
    double timestamp = 0.0;
    KeyFrameId reference = kNoId;
    SE3d cam_from_reference;
  };

  // Logs ok -> lost -> relocalized (or ok again) at debug level (`dlslam run`
  // logs the transitions with frame numbers) and counts relocalizations.
  void LogStateChange(const TrackingResult& result, double timestamp);
  // How the keyframe index and loop closing follow local mapping.
  KeyFrameHooks MappingHooks();
  // Tracking in a new map: every merge_every_frames-th frame is relocalized
  // in the older maps; when that succeeds, the new map is moved onto the
  // older one (local mapping paused) and tracking goes on there. The
  // merged frame counts as tracked.
  void TryMergeNewMap(const Frame& frame, const TrackingResult& result);

  CameraIntrinsics camera_;
  SystemOptions options_;
  features::OrbExtractor extractor_;
  features::OrbExtractor static_extractor_;  // re-extraction outside removed regions
  ScalePyramid pyramid_;
  StageTimings timings_;  // before mapper_: the mapping thread writes to it
  Map map_;
  std::unique_ptr<place::KeyFrameIndex> index_;  // null without relocalization and loop closing
  Tracker tracker_;
  DynamicStage dynamic_;
  LocalMapper mapper_;
  std::unique_ptr<LoopCloser> loop_closer_;  // null without loop closing
  // The network in its thread; null in modes orb and geometry, or without
  // options.semantic.network.
  std::unique_ptr<SemanticFeed> semantic_;
  // A keyframe waiting for its frame's own masks (one at a time).
  struct HeldKeyFrame {
    KeyFrameCandidate candidate;
    std::shared_future<semantic::SegmentationResult> masks;
    int frames_waited = 0;
    double timestamp = 0.0;
    cv::Mat colour, depth, removed;  // for keep_keyframe_images
  };
  // Inserts the held keyframe when its masks are there, or, with `wait` or
  // after keyframe_mask_max_wait_frames, once they are.
  void ReleaseHeldKeyFrame(bool wait);
  // Waits for local mapping when it lags (SystemOptions::max_mapping_lag_frames).
  void BoundMappingLag(long frame_id, double timestamp);
  // The keyframe enters the map: images kept, handed to local mapping.
  void KeyFrameMade(KeyFrameId id, double timestamp, const cv::Mat& colour, const cv::Mat& depth,
                    const cv::Mat& removed);
  std::optional<HeldKeyFrame> held_keyframe_;
  // Throws dlslam::Error for an empty colour image or one of another size than the camera's.
  void CheckColour(const cv::Mat& colour, double timestamp) const;
  // The frame's ORB features, outside what the prior removes for good
  // (SystemOptions::extract_outside_prior); `*used`: the extractor that ran
  // (a re-extraction reuses its work).
  features::OrbFeatures ExtractOutside(const cv::Mat& colour, const DynamicPrior& prior,
                                       const features::OrbExtractor** used);
  // Keyframes' images for the dense map (options.keep_keyframe_images).
  struct KeyFrameImages {
    double timestamp = 0.0;
    cv::Mat colour;   // CV_8UC3 BGR
    cv::Mat depth_mm; // CV_16UC1 millimetres, 0 = none (half the memory of metres as float)
    cv::Mat removed;  // CV_8UC1, 255 = removed as dynamic; empty = nothing removed
  };
  void KeepKeyFrameImages(KeyFrameId id, double timestamp, const cv::Mat& colour, const cv::Mat& depth,
                          const cv::Mat& removed);
  std::map<KeyFrameId, KeyFrameImages> keyframe_images_;
  std::vector<FrameRecord> tracked_;
  // Keyframes handed to local mapping and not known to be finished: the frame
  // that made each (number, timestamp, when its tracking began), and its
  // LocalMapper ticket.
  struct UnmappedKeyFrame {
    long frame = 0;
    double timestamp = 0.0;
    std::chrono::steady_clock::time_point frame_started;
    std::uint64_t ticket = 0;
  };
  std::deque<UnmappedKeyFrame> unmapped_;
  std::chrono::steady_clock::time_point frame_started_;  // of the frame being tracked
  std::vector<FramePoseSource> sources_;
  RunStats counts_;
  TrackingState last_state_ = TrackingState::kNotInitialized;  // for the state log
  bool shut_down_ = false;
  FrameView last_view_;
  double last_removed_share_ = 0.0;  // of the last frame's pixels, removed as dynamic
  int frames_in_new_map_ = 0;  // tracked frames since the current new map started
  std::optional<SE3d> pending_merge_;  // the last try's new_world_from_old_world, to be confirmed
};

}  // namespace dlslam

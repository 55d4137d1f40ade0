#pragma once
// Frame-to-map tracking (ORB-SLAM's Tracking for RGB-D, without the map
// management that local mapping owns):
//   1. the first frame with enough depth starts the map;
//   2. a constant-velocity guess, refined by matching the last frame's points
//      by projection (radius doubled on failure), or, if that fails, by
//      descriptor matching against the reference keyframe;
//   3. the local map (covisible keyframes' points) is projected and matched,
//      and the pose optimised again;
//   (after 2 and 3: a pose departing from the prediction by centimetres is
//      solved again on the matches the prediction explains: people pulling
//      it; TrackerOptions::gate_departure_m)
//   4. a keyframe is requested when tracking weakens (never from a gated pose).
// A frame that cannot be tracked (people covering the view, a blur) coasts:
// it gets the motion model's pose (refined on what few matches there are
// when they agree with it) and is reported as coasting, for up to
// max_coasting_frames; meanwhile the map is searched around the coasted pose
// and relocalization is tried; the first frame tracked again may move far
// from the coasted pose only on a relocalization's support. After that the
// frame is lost; the next frames try to relocalize against the whole map
// (relocalizer.h, when the tracker has a keyframe index), then the last
// reference keyframe. When that keeps failing (the camera went where the map
// has never been while it was covered), a new map starts at the last pose
// there was (ORB-SLAM3's Atlas idea, in one Map: the new map's first keyframe
// is an anchor, Map::SetAnchor);
// FindInOlderMaps / MergedIntoOlderMap let the system join it to the older
// map once a frame relocalizes there.

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map.h"
#include "dlslam/match/projection_matcher.h"
#include "dlslam/optimize/pose_optimizer.h"
#include "dlslam/tracking/relocalizer.h"

namespace dlslam {

struct TrackerOptions {
  // Keypoints with depth needed to start the map from one frame...
  int min_init_points = 500;
  // ... or at least this many when they are spread over the view: in at
  // least min_init_cells cells of a 4 x 4 grid, with 5 or more in each (0 =
  // off). When people cover most of the first frames, what is left of the
  // static scene may hold fewer than 500 keypoints for many frames, and
  // tracking needs only min_local_map_inliers of them; spread, they fix
  // the pose in every direction, bunched in one corner they do not.
  int min_init_points_spread = 150;
  int min_init_cells = 4;
  // Projection search around the constant-velocity guess [px at level 0].
  double motion_search_radius = 15.0;
  // Projection search for the local map [px at level 0] (ORB-SLAM: 4 px for
  // oblique views, tightened by pose accuracy).
  double local_search_radius = 4.0;
  // Matches needed after the motion-model search before optimising.
  int min_motion_matches = 20;
  // Inliers needed after the reference-keyframe fallback.
  int min_reference_inliers = 10;
  // Inliers needed after tracking the local map for the frame to count as tracked.
  int min_local_map_inliers = 30;
  // Keyframes in the local map.
  int max_local_keyframes = 40;
  // Keypoints closer than this [m] are "close": their depth is reliable
  // (ORB-SLAM's ThDepth * baseline, ~3 m for a Kinect).
  double close_depth = 3.0;
  // New keyframe when the frame tracks fewer than this fraction of the
  // reference keyframe's points (ORB-SLAM's RGB-D value 0.75) ...
  double keyframe_tracked_ratio = 0.75;
  // ... or after this many frames (about a second of video; ORB-SLAM's).
  int max_frames_between_keyframes = 30;
  // ... in the modes that remove moving content (semantic, geometry, full;
  // SlamSystem sets max_frames_between_keyframes to it). In a crowd the
  // tracked share falls slowly while the error grows: real Bonn crowd frames
  // 63-73 went 15 frames without a keyframe at 3-5 cm of error. Every 10
  // frames: Bonn full 0.0167 -> 0.0140 m sequential, threaded median 0.0166
  // -> 0.0147 m with the same keyframe count; a static scene gets twice the
  // keyframes (7-Scenes kitchen 25 -> 57), which mode orb's 8 ms frames
  // would feel (10.6 ms median, p95 19 ms) and full mode's do not.
  int max_frames_between_keyframes_dynamic = 10;
  // A frame whose removed share (the dynamic stage's mask, of the image)
  // is at least this is crowded: there, many untracked close keypoints do
  // not make a keyframe (ORB-SLAM's close-point rule), only tracking
  // weakening (keyframe_tracked_ratio) or the timeout do [0, 1]; 1 = off.
  // In a crowd the untracked close keypoints are mostly on people the mask
  // missed and on their outlines: the rule fired every other frame there,
  // wrote them into the map as points, and the next frames tracked the
  // walkers (semi-real kitchen, 8 people, seed 1: 0.132 m, 3.7x the
  // kitchen without people). 0.4 and 0.5 gave the same on the battery of
  // docs/real-data.md: Bonn full 0.0131 -> 0.0125 m, the 12 semi-real
  // kitchens' sum 0.546 -> 0.478 m (k8s1 0.132 -> 0.047, k5s8 0.056 ->
  // 0.078). Dropping every keyframe in a crowd but the timeout's instead
  // was chaotic (sum 0.446 / 0.529 / 0.560 m at 0.5 / 0.4 / 0.6).
  double crowded_removed_share = 0.5;
  // No new keyframe while this many wait for local mapping (ORB-SLAM: 3): it
  // would only wait in the queue, and tracking with it (SetMappingBacklog).
  int max_mapping_backlog = 3;
  // A keyframe creates points for its closest unmatched keypoints with depth:
  // all closer than close_depth, and at least this many.
  int min_new_points = 100;
  PoseOptimizerOptions pose;
  // Frames in a row that may coast on the motion model when tracking fails
  // (0 = none: a failure is lost at once) [frames; 10 = 1/3 s at 30 Hz,
  // about how long a person walking past covers the view].
  int max_coasting_frames = 10;
  // Coasting moves on the median (per component of the se(3) logarithm) of
  // the frame-to-frame motions of the last this many tracked frames, not on
  // the last one alone [frames, >= 1; 1 = the last motion]: the frame
  // before a failure is often the failure's start, a pose pulled by the
  // people now covering the view (semi-real kitchen, 5 walkers: 0.115 m in
  // the frame before coasting where the camera moved 8 mm, then 0.115 m per
  // coasted frame, 0.6 m off after 6).
  int coasting_velocity_frames = 10;
  // A coasting frame's pose is refined on its local-map matches when at
  // least this many are inliers and the refined pose stays within
  // max_coasting_correction of the prediction; otherwise it is the
  // prediction itself.
  int min_coasting_inliers = 10;
  double max_coasting_correction_m = 0.05;
  double max_coasting_correction_deg = 3.0;
  // A tracked pose that departs from the constant-velocity prediction by
  // more than these rates times the time since the last frame (at least
  // 1/30 s) is a wrong solution, not motion (people walking together in
  // front of the camera taken for the scene): the frame coasts instead, and
  // relocalization may take over from the next frame. The departure holds
  // the prediction's own error too: tracked frames of the real Bonn crowd
  // depart by up to 0.11 m (3.3 m/s), a wrong lock on walking people by
  // 0.4-0.9 m in one frame. 8 m/s, 360 deg/s: 0.27 m, 12 deg at 30 Hz.
  double max_jump_speed = 8.0;   // [m/s]
  double max_jump_rate = 360.0;  // [deg/s]
  // A tracked pose that departs from the constant-velocity prediction by
  // more than gate_departure_m or gate_departure_deg is solved again on the
  // local-map matches that project within gate_radius_px (times the
  // keypoint's pyramid scale) of their keypoints at the prediction; when
  // at least min_local_map_inliers of those are inliers, that pose is taken.
  // A handheld camera's motion changes by millimetres between frames; a
  // pose pulled by people (keypoints on a walker's outline or on clothes
  // the mask missed, moving 3-10 cm a frame) departs by centimetres, and
  // the pulling matches lie far from their keypoints at the prediction.
  // 0 = off. On 12 semi-real kitchens (docs/real-data.md) full mode's
  // median ATE 0.046 -> 0.042 m, geometry's sum over 5 of them 1.18 ->
  // 0.55 m; the real Bonn frames within their spread (8 of 300 gated).
  double gate_departure_m = 0.03;
  double gate_departure_deg = 2.0;
  double gate_radius_px = 6.0;
  // A pose that still departs that far after the gate is refused: the
  // frame coasts, as after a jump (max_jump_speed). Off: the real Bonn
  // frames depart by up to 0.11 m when tracked right (sensor jitter), and
  // refusing those cost 0.0157 -> 0.0177 m there (12 frames coasted).
  bool gate_refuses = false;
  // The gate's prediction moves on the median of the recent motions
  // (coasting_velocity_frames of them) instead of the last one, which holds
  // two poses' jitter and whatever pulled the last frame: on the last
  // motion, a pull below the gate's threshold enters the velocity, the
  // next prediction carries it twice over, and the gate then holds the
  // right pose near that wrong prediction for good (test
  // Tracker.TheMedianMotionGateLetsGoOfAPullThatHasEnded). Real 7-Scenes
  // kitchen (static) orb 0.0373 -> 0.0347 m, full 0.0380 -> 0.0329 m;
  // Bonn threaded full the same (7 runs each, medians 0.0172 / 0.0176 m).
  bool gate_on_median_motion = true;
  // A gated frame becomes a keyframe (when one is due) only if the solve
  // near the prediction kept at least this many inliers (0 = never). With
  // none the map falls behind a moving camera in a crowd: semi-real k5s8
  // (people on 70-85 % of the view, the camera at 45 cm/s) went 17 gated
  // frames without one, its matches fell to 26 and the pose slid 10 cm
  // (0.120 -> 0.056 m with 100). Few inliers still make none: five
  // keyframes in five weakly supported gated frames once slid 0.5 m.
  // SlamSystem uses it in the modes with the network's masks (semantic,
  // full) and 0 in modes orb and geometry, where the inliers near the
  // prediction may be people (Bonn geometry 0.080 -> 0.35 m with 100).
  int gated_keyframe_min_inliers = 100;
  // The N-th frame in a row that would have no pose (tracking, coasting and
  // relocalization all failed on it) starts a new map at the last pose
  // instead (0 = never: stay lost) [frames; 1 = at once]. Coasting has
  // tried relocalization on every covered frame already; the old default
  // (6 frames without a pose per loss) left semi-real crowds at 98.6-98.8 %
  // posed. At once (1), a map started inside the crowd drifted up to 1 m
  // before the old map was found again (docs/real-data.md); 3 leaves two
  // frames without a pose per loss for the crowd to pass.
  int new_map_after_lost_frames = 3;
  // false: localization only, the map is never extended (a loaded map).
  bool insert_keyframes = true;
  // Used when the tracker is given a keyframe index.
  RelocalizerOptions relocalization;

  void Check() const;
};

// A keyframe the tracker wanted but held back (Track with hold_keyframe):
// the caller inserts it later with InsertHeldKeyFrame, e.g. once the frame's
// own segmentation has arrived.
struct KeyFrameCandidate {
  std::shared_ptr<const Frame> frame;
  SE3d cam_from_world;
  std::vector<MapPointId> matches;  // per keypoint of frame; kNoId if none
  std::uint64_t generation = 0;     // Map::Generation() when it was tracked
};

// kCoasting: the frame has a pose from the motion model, not confirmed by
// the map (too few inliers); no keyframe is made from it.
enum class TrackingState { kNotInitialized, kOk, kCoasting, kLost };
const char* ToString(TrackingState state);

struct TrackingResult {
  TrackingState state = TrackingState::kNotInitialized;
  std::optional<SE3d> cam_from_world;  // set when tracked
  int matches = 0;                     // map points matched before the final optimisation
  int inliers = 0;                     // after it
  bool new_keyframe = false;
  KeyFrameId reference_keyframe = kNoId;
  // The pose relative to reference_keyframe, taken as it was tracked: it
  // stays right when loop closing moves the map afterwards.
  SE3d cam_from_reference;
  // Lost before, tracked again through relocalization against this keyframe.
  bool relocalized = false;
  KeyFrameId relocalization_keyframe = kNoId;
  // Time spent in relocalization for this frame [ms]; < 0: not attempted.
  double relocalization_ms = -1.0;
  // The map gave a pose too far from the prediction to be motion
  // (TrackerOptions::max_jump_speed): refused, the frame coasted or was lost.
  bool jump_refused = false;
  // The pose departed from the prediction and was solved again on the
  // matches the prediction explains (TrackerOptions::gate_departure_m).
  bool gated = false;
  // Lost for too long: this frame started a new map (its first keyframe).
  bool new_map = false;
  // Track(frame, /*hold_keyframe=*/true) on a frame that should become a
  // keyframe: the keyframe not made (new_keyframe stays false).
  std::optional<KeyFrameCandidate> held_keyframe;
};

// Is there enough static structure in `frame` to start a map on it
// (TrackerOptions::min_init_points, or min_init_points_spread spread over
// min_init_cells)?
bool CanStartMap(const Frame& frame, const TrackerOptions& options);

// What the system knows of a frame besides its keypoints.
struct TrackContext {
  // A keyframe this frame would make is returned as
  // TrackingResult::held_keyframe instead (a map's first keyframe never is).
  bool hold_keyframe = false;
  // Share of the image the dynamic stage removed, in [0, 1]
  // (TrackerOptions::crowded_removed_share).
  double removed_share = 0.0;
};

class Tracker {
 public:
  // With `index` (outlives the tracker; may be filled by another thread) a
  // lost tracker relocalizes; without, it only retries its reference keyframe.
  Tracker(const TrackerOptions& options, Map* map, const place::KeyFrameIndex* index = nullptr);

  // Tracks one frame (its static keypoints: Frame::WithoutMasked).
  TrackingResult Track(const std::shared_ptr<const Frame>& frame, const TrackContext& context = {});
  // Makes a held keyframe of the keypoints of `candidate` that `keep` marks
  // (e.g. those outside the frame's own person mask); the frames tracked
  // since go on as they were. nullopt when the map moved since it was
  // tracked (loop closing, a merge: its pose is from before) or too few of
  // its matches are kept.
  std::optional<KeyFrameId> InsertHeldKeyFrame(const KeyFrameCandidate& candidate, const std::vector<bool>& keep);

  // A first pose for the next frame, without changing the tracker: the
  // constant-velocity guess refined on the frame's keypoints
  // (matched to the last frame's points), or the guess itself when that
  // refinement fails. nullopt unless the last frame was tracked. The dynamic
  // stage uses it to test keypoints before the frame is tracked.
  std::optional<SE3d> EstimatePose(const Frame& frame) const;

  // Starts in a map that already exists (a loaded one): the next frame is
  // relocalized against it instead of starting a new map; `reference`
  // (e.g. the newest keyframe) is where the reference-keyframe fallback looks.
  void StartInMap(KeyFrameId reference);

  // How many keyframes wait for local mapping; unset = none. Called on the
  // tracking thread for every keyframe decision, so it must be cheap.
  void SetMappingBacklog(std::function<std::size_t()> backlog) { mapping_backlog_ = std::move(backlog); }

  TrackingState state() const { return state_; }
  // The constant-velocity guess of the next frame's cam_from_world; nullopt
  // before the first tracked frame.
  std::optional<SE3d> PredictedCamFromWorld() const {
    return last_pose_ ? std::optional<SE3d>(PredictedPose()) : std::nullopt;
  }
  // Tracking in a map started after a loss that has not been merged into an
  // older one yet: its first keyframe; nullopt otherwise.
  std::optional<KeyFrameId> new_map_origin() const {
    return origins_.empty() ? std::nullopt : std::optional<KeyFrameId>(origins_.back());
  }
  // Relocalizes `frame` in the maps older than the current new map (their
  // keyframes only) and refines the pose on their local map; nullopt when
  // there is none or it fails.
  std::optional<Relocalization> FindInOlderMaps(const Frame& frame);
  // After the caller moved the current new map onto the older map where
  // `found` (from FindInOlderMaps) put the frame: the new map is merged (its
  // anchor cleared) and tracking goes on from `found`'s pose and matches.
  void MergedIntoOlderMap(const Relocalization& found);
  // The keyframe the last tracked frame shares most points with.
  KeyFrameId reference_keyframe() const { return reference_keyframe_; }

 private:
  // Starts a map with `frame` as its first keyframe at `pose`; false when the
  // frame has too few keypoints with depth.
  bool StartMap(const std::shared_ptr<const Frame>& frame, const SE3d& pose, TrackingResult* result);
  // The coasting pose of a frame that failed to track: `refined` (the local
  // map's optimisation, `inliers` of them) when it agrees with the
  // prediction, else the prediction. False when the frame may not coast.
  bool Coast(const SE3d& refined, int inliers, SE3d* pose) const;
  // True when `pose` departs from the prediction faster than the camera can
  // move (TrackerOptions::max_jump_speed, max_jump_rate).
  bool IsJump(const SE3d& pose, double timestamp) const;
  // True when `pose`, the first tracked after coasting on `inliers`, corrects
  // the coasted prediction by more than the coasting can have drifted (the
  // coasting correction bound plus twice the coasting velocity per frame
  // coasted: a camera that stopped, or turned back) with less support than
  // a relocalization needs. In a crowd the frame that "tracks again" after
  // a few covered ones is often a walker's unmasked clothes.
  bool ImplausibleAfterCoasting(const SE3d& pose, int inliers) const;
  // Pose from the last frame's points with the constant-velocity guess.
  // `gated` (optional): set when the pose was solved again near the prediction.
  bool TrackWithMotionModel(const Frame& frame, SE3d* pose, std::vector<MapPointId>* matches,
                            bool* gated = nullptr) const;
  // Pose from descriptor matches against the reference keyframe.
  bool TrackReferenceKeyFrame(const Frame& frame, SE3d* pose, std::vector<MapPointId>* matches);
  // Adds local-map matches and re-optimises; returns the inlier count.
  // `searched` (optional): the matches before the outliers were dropped.
  int TrackLocalMap(const Frame& frame, SE3d* pose, std::vector<MapPointId>* matches, KeyFrameId* reference,
                    std::vector<MapPointId>* searched = nullptr);
  // The pose solved again on the matches of `searched` near the prediction
  // (TrackerOptions::gate_departure_m) when `pose` departs from it; true
  // when it replaced `pose` and `matches`.
  bool GateOnPrediction(const Frame& frame, const std::vector<MapPointId>& searched, SE3d* pose,
                        std::vector<MapPointId>* matches, int* inliers) const;
  // True when the gate is on and `pose` departs from the prediction by more than it allows.
  bool GateDeparts(const SE3d& pose) const;
  // The pose the gate measures against (TrackerOptions::gate_on_median_motion).
  SE3d GatePrediction() const;
  // True when `pose` departs from `reference` by more than `metres` or `degrees`.
  static bool Departs(const SE3d& pose, const SE3d& reference, double metres, double degrees);
  // Optimises the pose on the matches; drops outliers; returns inliers.
  int OptimizeAndPrune(const Frame& frame, const std::vector<MapPointView>& points, SE3d* pose,
                       std::vector<MapPointId>* matches) const;
  // The last tracked frame's pose in the map as it is now: loop closing may
  // have moved the map since (Map::Generation), and the frame moves with the
  // keyframe it was tracked against.
  SE3d LastPose() const;
  // The constant-velocity prediction from LastPose (LastPose itself without a velocity).
  SE3d PredictedPose() const;
  // The median of recent_motions_ (TrackerOptions::coasting_velocity_frames).
  SE3d CoastingVelocity() const;
  // No motion model: the velocity and the motions it is taken from.
  void ForgetMotion();
  // `generation`: the map's when the pose was computed.
  void RememberPose(const SE3d& pose, KeyFrameId reference, std::uint64_t generation);
  bool NeedNewKeyFrame(const Frame& frame, const std::vector<MapPointId>& matches, KeyFrameId reference,
                       bool crowded) const;
  // Adds the keyframe and its new points; the next frame searches its points
  // unless `search_its_points` is false (a held keyframe, older than the
  // last frame).
  KeyFrameId InsertKeyFrame(const std::shared_ptr<const Frame>& frame, const SE3d& pose,
                            const std::vector<MapPointId>& matches, bool all_depth_points = false,
                            bool search_its_points = true);

  TrackerOptions options_;
  Map* map_;
  std::function<std::size_t()> mapping_backlog_;
  std::optional<Relocalizer> relocalizer_;
  TrackingState state_ = TrackingState::kNotInitialized;
  // The last tracked frame: its pose, matched points and the motion into it.
  std::optional<SE3d> last_pose_;
  std::uint64_t last_pose_generation_ = 0;  // Map::Generation() when last_pose_ was set
  KeyFrameId last_pose_reference_ = kNoId;  // the keyframe it was tracked against
  std::optional<SE3d> last_from_reference_;  // cam_last_from_cam_reference then
  std::optional<SE3d> velocity_;  // cam_from_world_last * world_from_cam_before_last
  // se(3) logarithms of the velocities of the last tracked frames (not
  // coasted, not back from a loss), newest last; for CoastingVelocity and
  // the gate's prediction.
  std::deque<Eigen::Matrix<double, 6, 1>> recent_motions_;
  // The last pose is the first one back from a loss (relocalized, or found
  // from the reference keyframe): the step from it corrects it rather than
  // moving the camera, so it is neither a velocity nor a prediction to refuse by.
  bool last_pose_recovered_ = false;
  std::vector<MapPointId> last_matches_;
  KeyFrameId reference_keyframe_ = kNoId;
  int frames_since_keyframe_ = 0;
  int coasted_frames_ = 0;  // in a row, up to the current frame
  int lost_frames_ = 0;     // frames without a pose in a row, before the current one
  // First keyframes of the maps started after a loss and not merged, oldest first.
  std::vector<KeyFrameId> origins_;
  double last_timestamp_ = 0.0;  // of the last frame with a pose
};

}  // namespace dlslam

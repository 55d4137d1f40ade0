#include "dlslam/tracking/tracker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "dlslam/tracking/matched_pose.h"
#include "dlslam/util/check.h"
#include "dlslam/util/timing.h"

namespace dlslam {

namespace {
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// A keyframe needs this many tracked points (ORB-SLAM: more than 15).
constexpr int kMinKeyFrameMatches = 16;
// The start rule's grid (kInitGrid x kInitGrid cells) and the keypoints a
// cell needs to count.
constexpr int kInitGrid = 4;
constexpr int kInitCellPoints = 5;
}  // namespace

void TrackerOptions::Check() const {
  DLSLAM_CHECK_GT(min_init_points, 0);
  DLSLAM_CHECK(min_init_points_spread >= 0 && min_init_points_spread <= min_init_points,
               "TrackerOptions::min_init_points_spread {} outside [0, min_init_points {}]", min_init_points_spread,
               min_init_points);
  DLSLAM_CHECK(min_init_cells >= 1 && min_init_cells <= kInitGrid * kInitGrid,
               "TrackerOptions::min_init_cells {} outside [1, {}]", min_init_cells, kInitGrid * kInitGrid);
  DLSLAM_CHECK_GT(motion_search_radius, 0.0);
  DLSLAM_CHECK_GT(local_search_radius, 0.0);
  DLSLAM_CHECK_GE(min_motion_matches, 3);
  DLSLAM_CHECK_GE(min_reference_inliers, 3);
  DLSLAM_CHECK_GE(min_local_map_inliers, 3);
  DLSLAM_CHECK_GT(max_local_keyframes, 0);
  DLSLAM_CHECK_GT(close_depth, 0.0);
  DLSLAM_CHECK(keyframe_tracked_ratio > 0 && keyframe_tracked_ratio <= 1);
  DLSLAM_CHECK_GT(max_frames_between_keyframes, 0);
  DLSLAM_CHECK_GT(max_frames_between_keyframes_dynamic, 0);
  DLSLAM_CHECK_GE(gated_keyframe_min_inliers, 0);
  DLSLAM_CHECK(crowded_removed_share >= 0 && crowded_removed_share <= 1,
               "TrackerOptions::crowded_removed_share {} outside [0, 1]", crowded_removed_share);
  DLSLAM_CHECK_GT(max_mapping_backlog, 0);
  DLSLAM_CHECK_GE(min_new_points, 0);
  DLSLAM_CHECK(max_coasting_frames >= 0 && max_coasting_frames <= 1000,
               "TrackerOptions::max_coasting_frames {} outside [0, 1000]", max_coasting_frames);
  DLSLAM_CHECK_GE(min_coasting_inliers, 3);
  DLSLAM_CHECK(coasting_velocity_frames >= 1 && coasting_velocity_frames <= 1000,
               "TrackerOptions::coasting_velocity_frames {} outside [1, 1000]", coasting_velocity_frames);
  DLSLAM_CHECK(max_coasting_correction_m > 0 && max_coasting_correction_deg > 0,
               "TrackerOptions::max_coasting_correction {} m, {} deg must be > 0", max_coasting_correction_m,
               max_coasting_correction_deg);
  DLSLAM_CHECK(new_map_after_lost_frames >= 0 && new_map_after_lost_frames <= 100000,
               "TrackerOptions::new_map_after_lost_frames {} outside [0, 100000]", new_map_after_lost_frames);
  DLSLAM_CHECK(max_jump_speed > 0 && max_jump_rate > 0,
               "TrackerOptions::max_jump_speed {} m/s, max_jump_rate {} deg/s must be > 0", max_jump_speed,
               max_jump_rate);
  DLSLAM_CHECK(gate_departure_m >= 0 && gate_departure_deg >= 0 && gate_radius_px > 0,
               "TrackerOptions::gate_departure {} m, {} deg must be >= 0, gate_radius_px {} > 0", gate_departure_m,
               gate_departure_deg, gate_radius_px);
  pose.Check();
  relocalization.Check();
}

const char* ToString(TrackingState state) {
  switch (state) {
    case TrackingState::kNotInitialized: return "not_initialized";
    case TrackingState::kOk: return "ok";
    case TrackingState::kCoasting: return "coasting";
    case TrackingState::kLost: return "lost";
  }
  return "?";
}


Tracker::Tracker(const TrackerOptions& options, Map* map, const place::KeyFrameIndex* index)
    : options_(options), map_(map) {
  options_.Check();
  DLSLAM_CHECK(map_ != nullptr);
  if (index != nullptr) relocalizer_.emplace(options_.relocalization, map_, index);
}

TrackingResult Tracker::Track(const std::shared_ptr<const Frame>& frame, const TrackContext& context) {
  DLSLAM_CHECK(frame != nullptr);
  DLSLAM_CHECK(context.removed_share >= 0 && context.removed_share <= 1, "TrackContext::removed_share {} outside [0, 1]",
               context.removed_share);
  TrackingResult result;
  if (state_ == TrackingState::kNotInitialized) {
    if (StartMap(frame, SE3d::Identity(), &result)) state_ = TrackingState::kOk;  // the first keyframe defines the world
    result.state = state_;
    return result;
  }
  const std::uint64_t generation = map_->Generation();
  if (last_pose_) last_pose_ = LastPose();
  last_pose_generation_ = generation;
  SE3d pose;
  std::vector<MapPointId> matches;
  bool ok = false;
  const bool coasting = state_ == TrackingState::kCoasting;
  if ((state_ == TrackingState::kOk || coasting) && velocity_) {
    ok = TrackWithMotionModel(*frame, &pose, &matches, &result.gated);
  }
  if (!ok && (state_ == TrackingState::kLost || coasting) && relocalizer_) {
    const Stopwatch watch;
    const RelocalizationAttempt attempt = relocalizer_->Relocalize(*frame);
    result.relocalization_ms = watch.ElapsedMs();
    if (attempt.result) {
      ok = true;
      pose = attempt.result->cam_from_world;
      matches = attempt.result->matches;
      reference_keyframe_ = attempt.result->keyframe;
      // Found in an older map: the new maps after it are left as they are.
      while (!origins_.empty() && origins_.back() > reference_keyframe_) origins_.pop_back();
      result.relocalized = true;
      result.relocalization_keyframe = attempt.result->keyframe;
    }
  }
  if (!ok) ok = TrackReferenceKeyFrame(*frame, &pose, &matches);
  KeyFrameId reference = reference_keyframe_;
  bool searched_local_map = false;
  if (ok) {
    result.matches = CountMatches(matches);
    std::vector<MapPointId> searched;
    result.inliers = TrackLocalMap(*frame, &pose, &matches, &reference, &searched);
    searched_local_map = true;
    bool departs = false;
    if (state_ == TrackingState::kOk && !result.relocalized && velocity_) {
      result.gated |= GateOnPrediction(*frame, searched, &pose, &matches, &result.inliers);
      departs = options_.gate_refuses && GateDeparts(pose);
    }
    ok = result.inliers >= options_.min_local_map_inliers;
    // Only a tracked camera has a prediction worth trusting: not one just
    // found again, whose pose may be off by more than a frame's motion; a
    // coasting one bounds how far the first frame back may move.
    const bool tracked = state_ == TrackingState::kOk && !last_pose_recovered_;
    if (ok && !result.relocalized &&
        ((tracked && (departs || IsJump(pose, frame->timestamp()))) ||
         (coasting && ImplausibleAfterCoasting(pose, result.inliers)))) {
      ok = false;
      result.jump_refused = true;
    }
  }
  SE3d coasted;
  // Coasting starts: on the recent motion, not on the last frame's alone.
  if (!ok && state_ == TrackingState::kOk && !recent_motions_.empty()) velocity_ = CoastingVelocity();
  if (!ok && Coast(pose, searched_local_map ? result.inliers : 0, &coasted)) {
    state_ = TrackingState::kCoasting;
    ++coasted_frames_;
    // The motion model goes on; the last tracked frame's points stay the
    // ones searched next (last_matches_), now around the coasted pose.
    RememberPose(coasted, reference_keyframe_, generation);
    last_timestamp_ = frame->timestamp();
    result.relocalized = false;
    result.relocalization_keyframe = kNoId;
    result.state = state_;
    result.cam_from_world = coasted;
    result.reference_keyframe = reference_keyframe_;
    result.cam_from_reference = last_from_reference_.value_or(SE3d::Identity());
    return result;
  }
  if (!ok && options_.insert_keyframes && options_.new_map_after_lost_frames > 0 &&
      lost_frames_ + 1 >= options_.new_map_after_lost_frames) {
    // Where the camera was last seen is the best guess of where it is.
    const SE3d start = last_pose_ ? LastPose() : SE3d::Identity();
    if (StartMap(frame, start, &result)) {
      map_->SetAnchor(reference_keyframe_);
      origins_.push_back(reference_keyframe_);
      state_ = TrackingState::kOk;
      lost_frames_ = 0;
      coasted_frames_ = 0;
      result.state = state_;
      result.new_map = true;
      return result;
    }
  }
  if (!ok) {
    ++lost_frames_;
    state_ = TrackingState::kLost;
    ForgetMotion();
    result.relocalized = false;
    result.relocalization_keyframe = kNoId;
    result.state = state_;
    result.reference_keyframe = reference_keyframe_;
    return result;
  }
  const bool back_from_loss = state_ == TrackingState::kLost || result.relocalized;
  state_ = TrackingState::kOk;
  coasted_frames_ = 0;
  lost_frames_ = 0;
  reference_keyframe_ = reference;
  // Back from a loss (relocalized, or found again from the reference
  // keyframe) the last pose is from before it: no motion model. Back from
  // coasting, the step from the last coasted pose is mostly the coasting's
  // error being corrected, not the camera's motion: the motion model keeps
  // the coasting velocity (semi-real kitchen: a 0.24 m correction taken as
  // the velocity sent the next frames 0.2 m a frame the wrong way). The step
  // from the first pose back from a loss is that pose's correction: no
  // velocity either (semi-real kitchen: a relocalization 0.22 m off, its
  // correction taken as the velocity, and the next frames ran 2 m away).
  if (!last_pose_ || back_from_loss || last_pose_recovered_) {
    velocity_.reset();
    recent_motions_.clear();
  } else if (!coasting) {
    velocity_ = pose * last_pose_->Inverse();
    recent_motions_.push_back(velocity_->Log());
    while (recent_motions_.size() > static_cast<std::size_t>(options_.coasting_velocity_frames)) {
      recent_motions_.pop_front();
    }
  }
  last_pose_recovered_ = back_from_loss;
  ++frames_since_keyframe_;
  last_matches_ = matches;
  // A map moved by loop closing during this call: the pose is from before,
  // so it must not become a keyframe. Nor does a weakly supported gated
  // pose: the frame's matches disagreed about it, and a keyframe would
  // write points into the map that agree with it.
  const bool map_moved = map_->Generation() != generation;
  const bool gate_allows_keyframe =
      !result.gated ||
      (options_.gated_keyframe_min_inliers > 0 && result.inliers >= options_.gated_keyframe_min_inliers);
  const bool crowded = context.removed_share >= options_.crowded_removed_share;
  if (!map_moved && gate_allows_keyframe && NeedNewKeyFrame(*frame, matches, reference, crowded)) {
    if (context.hold_keyframe) {
      result.held_keyframe = KeyFrameCandidate{frame, pose, matches, generation};
    } else {
      reference_keyframe_ = InsertKeyFrame(frame, pose, matches);
      result.new_keyframe = true;
    }
  }
  RememberPose(pose, reference_keyframe_, generation);
  last_timestamp_ = frame->timestamp();
  result.state = state_;
  result.cam_from_world = pose;
  result.reference_keyframe = reference_keyframe_;
  result.cam_from_reference = last_from_reference_.value_or(SE3d::Identity());
  return result;
}

void Tracker::StartInMap(KeyFrameId reference) {
  DLSLAM_CHECK(state_ == TrackingState::kNotInitialized, "StartInMap before the first frame");
  state_ = TrackingState::kLost;
  reference_keyframe_ = reference;
  last_pose_.reset();
  ForgetMotion();
}

bool Tracker::Coast(const SE3d& refined, int inliers, SE3d* pose) const {
  if (coasted_frames_ >= options_.max_coasting_frames || !last_pose_) return false;
  if (state_ != TrackingState::kOk && state_ != TrackingState::kCoasting) return false;
  const SE3d predicted = PredictedPose();
  *pose = predicted;
  if (inliers < options_.min_coasting_inliers) return true;
  const SE3d correction = refined * predicted.Inverse();
  if (correction.translation().norm() <= options_.max_coasting_correction_m &&
      correction.so3().Log().norm() * kRadToDeg <= options_.max_coasting_correction_deg) {
    *pose = refined;
  }
  return true;
}

std::optional<Relocalization> Tracker::FindInOlderMaps(const Frame& frame) {
  if (origins_.empty() || !relocalizer_) return std::nullopt;
  std::optional<Relocalization> found = relocalizer_->Relocalize(frame, /*below=*/origins_.back()).result;
  if (!found) return std::nullopt;
  // Refined on the older map's local map, as tracking refines a
  // relocalization: the relocalization's pose alone scattered by 0.1-0.2 m
  // from frame to frame in the semi-real kitchen.
  KeyFrameId reference = found->keyframe;
  found->inliers = TrackLocalMap(frame, &found->cam_from_world, &found->matches, &reference);
  if (found->inliers < options_.min_local_map_inliers || reference >= origins_.back()) return std::nullopt;
  found->keyframe = reference;
  return found;
}

void Tracker::MergedIntoOlderMap(const Relocalization& found) {
  DLSLAM_CHECK(!origins_.empty() && found.keyframe < origins_.back(), "MergedIntoOlderMap without a new map");
  map_->ClearAnchor(origins_.back());
  origins_.pop_back();
  // The velocity is a motion between camera frames: it holds in any map.
  reference_keyframe_ = found.keyframe;
  last_matches_ = found.matches;
  RememberPose(found.cam_from_world, found.keyframe, map_->Generation());
}

bool CanStartMap(const Frame& frame, const TrackerOptions& options) {
  std::array<int, kInitGrid * kInitGrid> cells{};
  int with_depth = 0;
  const CameraIntrinsics& camera = frame.camera();
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const FrameKeypoint& k = frame.keypoint(i);
    if (!(k.depth > 0)) continue;
    ++with_depth;
    const int cx = std::clamp(static_cast<int>(k.raw_uv.x() * kInitGrid / camera.width), 0, kInitGrid - 1);
    const int cy = std::clamp(static_cast<int>(k.raw_uv.y() * kInitGrid / camera.height), 0, kInitGrid - 1);
    ++cells[static_cast<std::size_t>(cy * kInitGrid + cx)];
  }
  if (with_depth >= options.min_init_points) return true;
  if (options.min_init_points_spread == 0 || with_depth < options.min_init_points_spread) return false;
  const auto filled = std::count_if(cells.begin(), cells.end(), [](int n) { return n >= kInitCellPoints; });
  return filled >= options.min_init_cells;
}

bool Tracker::StartMap(const std::shared_ptr<const Frame>& frame, const SE3d& pose, TrackingResult* result) {
  if (!CanStartMap(*frame, options_)) return false;
  int with_depth = 0;
  for (std::size_t i = 0; i < frame->size(); ++i) with_depth += frame->keypoint(i).depth > 0;
  // The first keyframe takes every keypoint with depth (ORB-SLAM's RGB-D
  // initialisation); later ones only the close ones.
  reference_keyframe_ =
      InsertKeyFrame(frame, pose, std::vector<MapPointId>(frame->size(), kNoId), /*all_depth_points=*/true);
  RememberPose(pose, reference_keyframe_, map_->Generation());
  last_timestamp_ = frame->timestamp();
  ForgetMotion();
  result->cam_from_world = pose;
  result->cam_from_reference = SE3d::Identity();
  result->new_keyframe = true;
  result->reference_keyframe = reference_keyframe_;
  result->inliers = with_depth;
  return true;
}

std::optional<SE3d> Tracker::EstimatePose(const Frame& frame) const {
  if ((state_ != TrackingState::kOk && state_ != TrackingState::kCoasting) || !last_pose_) return std::nullopt;
  const SE3d guess = PredictedPose();
  SE3d pose;
  std::vector<MapPointId> matches;
  if (TrackWithMotionModel(frame, &pose, &matches)) return pose;
  return guess;
}

bool Tracker::TrackWithMotionModel(const Frame& frame, SE3d* pose, std::vector<MapPointId>* matches,
                                   bool* gated) const {
  *pose = PredictedPose();
  const std::vector<MapPointView> points = map_->GetPoints(MatchedIds(last_matches_));
  ProjectionMatchOptions search;
  search.radius = options_.motion_search_radius;
  matches->assign(frame.size(), kNoId);
  SearchByProjection(frame, *pose, points, search, matches);
  if (CountMatches(*matches) < options_.min_motion_matches) {
    search.radius *= 2;  // a sudden motion: look wider
    matches->assign(frame.size(), kNoId);
    SearchByProjection(frame, *pose, points, search, matches);
  }
  if (CountMatches(*matches) < options_.min_motion_matches) return false;
  const std::vector<MapPointId> searched = *matches;
  int inliers = OptimizeAndPrune(frame, points, pose, matches);
  const bool was_gated = GateOnPrediction(frame, searched, pose, matches, &inliers);
  if (gated != nullptr) *gated = was_gated;
  return inliers >= options_.min_motion_matches / 2;
}

bool Tracker::TrackReferenceKeyFrame(const Frame& frame, SE3d* pose, std::vector<MapPointId>* matches) {
  if (reference_keyframe_ == kNoId) return false;
  const std::optional<KeyFrameSnapshot> ref = map_->GetKeyFrame(reference_keyframe_);
  if (!ref) return false;
  *matches = MatchToKeyFrame(frame, *ref->frame, ref->points);
  if (CountMatches(*matches) < options_.min_reference_inliers) return false;
  *pose = last_pose_ ? LastPose() : ref->cam_from_world;
  const std::vector<MapPointView> points = map_->GetPoints(MatchedIds(*matches));
  return OptimizeAndPrune(frame, points, pose, matches) >= options_.min_reference_inliers;
}

bool Tracker::Departs(const SE3d& pose, const SE3d& reference, double metres, double degrees) {
  const SE3d departure = pose * reference.Inverse();
  return departure.translation().norm() > metres || departure.so3().Log().norm() * kRadToDeg > degrees;
}

bool Tracker::GateDeparts(const SE3d& pose) const {
  if (options_.gate_departure_m <= 0 && options_.gate_departure_deg <= 0) return false;
  const double metres = options_.gate_departure_m > 0 ? options_.gate_departure_m : INFINITY;
  const double degrees = options_.gate_departure_deg > 0 ? options_.gate_departure_deg : INFINITY;
  return Departs(pose, GatePrediction(), metres, degrees);
}

SE3d Tracker::GatePrediction() const {
  constexpr std::size_t kMinMotions = 3;  // a median of fewer is the last motion's noise again
  if (!options_.gate_on_median_motion || recent_motions_.size() < kMinMotions) return PredictedPose();
  return CoastingVelocity() * LastPose();
}

bool Tracker::GateOnPrediction(const Frame& frame, const std::vector<MapPointId>& searched, SE3d* pose,
                               std::vector<MapPointId>* matches, int* inliers) const {
  if (!GateDeparts(*pose)) return false;
  const SE3d predicted = GatePrediction();
  const std::vector<MapPointView> points = map_->GetPoints(MatchedIds(searched));
  std::vector<MapPointId> near = searched;
  KeepMatchesNear(frame, points, predicted, options_.gate_radius_px, &near);
  if (CountMatches(near) < options_.min_local_map_inliers) return false;
  SE3d gated = predicted;
  const int n = OptimizeAndPrune(frame, points, &gated, &near);
  if (n < options_.min_local_map_inliers) return false;
  *pose = gated;
  *matches = std::move(near);
  *inliers = n;
  return true;
}

int Tracker::TrackLocalMap(const Frame& frame, SE3d* pose, std::vector<MapPointId>* matches,
                           KeyFrameId* reference, std::vector<MapPointId>* searched) {
  const LocalMapSnapshot local = map_->GetLocalMap(MatchedIds(*matches), options_.max_local_keyframes);
  if (local.reference != kNoId) *reference = local.reference;
  ProjectionMatchOptions search;
  search.radius = options_.local_search_radius;
  // Points already matched are not searched again.
  std::vector<MapPointId> matched = MatchedIds(*matches);
  std::sort(matched.begin(), matched.end());
  std::vector<MapPointView> candidates;
  for (const MapPointView& p : local.points) {
    if (!std::binary_search(matched.begin(), matched.end(), p.id)) candidates.push_back(p);
  }
  const ProjectionMatchStats stats = SearchByProjection(frame, *pose, candidates, search, matches);
  std::vector<MapPointView> all = map_->GetPoints(MatchedIds(*matches));
  if (searched != nullptr) *searched = *matches;
  const int inliers = OptimizeAndPrune(frame, all, pose, matches);
  // Statistics for point culling: visible = projected into the frame; the
  // points matched before this search were visible too.
  std::vector<MapPointId> visible = stats.visible;
  visible.insert(visible.end(), matched.begin(), matched.end());
  map_->RecordVisibility(visible, MatchedIds(*matches));
  return inliers;
}

int Tracker::OptimizeAndPrune(const Frame& frame, const std::vector<MapPointView>& points, SE3d* pose,
                              std::vector<MapPointId>* matches) const {
  return dlslam::OptimizeAndPrune(frame, points, options_.pose, pose, matches);
}

bool Tracker::IsJump(const SE3d& pose, double timestamp) const {
  constexpr double kMinInterval = 1.0 / 30.0;  // [s]; also for timestamps that do not increase
  const double dt = std::max(timestamp - last_timestamp_, kMinInterval);
  return Departs(pose, PredictedPose(), options_.max_jump_speed * dt, options_.max_jump_rate * dt);
}

bool Tracker::ImplausibleAfterCoasting(const SE3d& pose, int inliers) const {
  if (inliers >= options_.relocalization.min_inliers) return false;
  const double frames = std::max(coasted_frames_, 1);
  const double speed_m = velocity_ ? velocity_->translation().norm() : 0.0;
  const double speed_deg = velocity_ ? velocity_->so3().Log().norm() * kRadToDeg : 0.0;
  return Departs(pose, PredictedPose(), options_.max_coasting_correction_m + 2.0 * speed_m * frames,
                 options_.max_coasting_correction_deg + 2.0 * speed_deg * frames);
}

SE3d Tracker::PredictedPose() const {
  // Right after a keyframe or a relocation there is no velocity: assume none.
  const SE3d last = LastPose();
  return velocity_ ? *velocity_ * last : last;
}

void Tracker::ForgetMotion() {
  velocity_.reset();
  recent_motions_.clear();
  last_pose_recovered_ = false;
}

SE3d Tracker::CoastingVelocity() const {
  DLSLAM_CHECK(!recent_motions_.empty());
  Eigen::Matrix<double, 6, 1> median;
  std::vector<double> values(recent_motions_.size());
  for (int c = 0; c < 6; ++c) {
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = recent_motions_[i][c];
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    median[c] = *middle;
  }
  return SE3d::Exp(median);
}

SE3d Tracker::LastPose() const {
  DLSLAM_CHECK(last_pose_.has_value());
  if (map_->Generation() == last_pose_generation_ || !last_from_reference_) return *last_pose_;
  const auto reference_now = map_->ResolveCamFromWorld(last_pose_reference_);
  if (!reference_now) return *last_pose_;
  return *last_from_reference_ * *reference_now;
}

void Tracker::RememberPose(const SE3d& pose, KeyFrameId reference, std::uint64_t generation) {
  last_pose_ = pose;
  last_pose_generation_ = generation;
  last_pose_reference_ = reference;
  const auto reference_pose = map_->ResolveCamFromWorld(reference);
  last_from_reference_ = reference_pose ? std::optional<SE3d>(pose * reference_pose->Inverse()) : std::nullopt;
}

bool Tracker::NeedNewKeyFrame(const Frame& frame, const std::vector<MapPointId>& matches, KeyFrameId reference,
                              bool crowded) const {
  if (!options_.insert_keyframes) return false;
  if (mapping_backlog_ && mapping_backlog_() >= static_cast<std::size_t>(options_.max_mapping_backlog)) return false;
  const int reference_tracked = map_->TrackedPoints(reference, map_->NumKeyFrames() <= 2 ? 2 : 3);
  const int tracked = CountMatches(matches);
  // Close keypoints: tracked ones anchor the pose; untracked ones would make good new points.
  int close_tracked = 0, close_untracked = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const double z = frame.keypoint(i).depth;
    if (z <= 0 || z >= options_.close_depth) continue;
    (matches[i] != kNoId ? close_tracked : close_untracked)++;
  }
  // In a crowd the untracked close keypoints are mostly on people (TrackerOptions::crowded_removed_share).
  const bool need_close = !crowded && close_tracked < 100 && close_untracked > 70;
  const bool weak = tracked < options_.keyframe_tracked_ratio * reference_tracked || need_close;
  const bool timeout = frames_since_keyframe_ >= options_.max_frames_between_keyframes;
  return (weak || timeout) && tracked >= kMinKeyFrameMatches;
}

KeyFrameId Tracker::InsertKeyFrame(const std::shared_ptr<const Frame>& frame, const SE3d& pose,
                                   const std::vector<MapPointId>& matches, bool all_depth_points,
                                   bool search_its_points) {
  const KeyFrameId kf = map_->AddKeyFrame(frame, pose);
  for (std::size_t i = 0; i < matches.size(); ++i) {
    if (matches[i] != kNoId) map_->AddObservation(matches[i], kf, static_cast<int>(i));
  }
  // New points from depth: the closest unmatched keypoints.
  std::vector<std::pair<double, int>> by_depth;
  for (std::size_t i = 0; i < frame->size(); ++i) {
    const double z = frame->keypoint(i).depth;
    if (matches[i] == kNoId && z > 0) by_depth.emplace_back(z, static_cast<int>(i));
  }
  std::sort(by_depth.begin(), by_depth.end());
  const SE3d world_from_cam = pose.Inverse();
  int created = 0;
  for (const auto& [z, i] : by_depth) {
    if (!all_depth_points && z >= options_.close_depth && created >= options_.min_new_points) break;
    map_->AddMapPoint(world_from_cam * *frame->Unproject(i), kf, i);
    ++created;
  }
  map_->UpdateConnections(kf);
  frames_since_keyframe_ = 0;
  // The next frame searches the keyframe's points, old and new.
  if (search_its_points) last_matches_ = map_->GetKeyFrame(kf)->points;
  return kf;
}

std::optional<KeyFrameId> Tracker::InsertHeldKeyFrame(const KeyFrameCandidate& candidate, const std::vector<bool>& keep) {
  DLSLAM_CHECK(candidate.frame != nullptr && keep.size() == candidate.frame->size() &&
                   candidate.matches.size() == keep.size(),
               "held keyframe: {} keep flags for {} keypoints", keep.size(), candidate.matches.size());
  if (map_->Generation() != candidate.generation) return std::nullopt;
  std::vector<MapPointId> matches;
  for (std::size_t i = 0; i < keep.size(); ++i) {
    if (keep[i]) matches.push_back(candidate.matches[i]);
  }
  if (CountMatches(matches) < kMinKeyFrameMatches) return std::nullopt;
  const auto frame = std::make_shared<const Frame>(candidate.frame->Subset(keep));
  const KeyFrameId kf = InsertKeyFrame(frame, candidate.cam_from_world, matches, /*all_depth_points=*/false,
                                       /*search_its_points=*/false);
  reference_keyframe_ = kf;
  return kf;
}

}  // namespace dlslam

#include "dlslam/loop/loop_detector.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <unordered_map>

#include "dlslam/tracking/matched_pose.h"
#include "dlslam/util/check.h"

namespace dlslam {

namespace {

// Every covisible keyframe, however weakly connected.
constexpr std::size_t kAllNeighbours = 100000;

std::unordered_map<MapPointId, Eigen::Vector3d> Positions(const std::vector<MapPointView>& points) {
  std::unordered_map<MapPointId, Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const MapPointView& p : points) out.emplace(p.id, p.position);
  return out;
}

}  // namespace

void LoopDetectorOptions::Check() const {
  DLSLAM_CHECK_GE(min_keyframes_between_loops, 0);
  DLSLAM_CHECK_GE(min_consistency, 1);
  candidates.Check();
  DLSLAM_CHECK_GE(min_bow_matches, 3, "min_bow_matches (RANSAC needs 3)");
  bow_match.Check();
  ransac.Check();
  DLSLAM_CHECK_GT(ransac_error_m, 0.0);
  DLSLAM_CHECK_GE(ransac_error_per_m2, 0.0);
  DLSLAM_CHECK_GE(loop_group_keyframes, 1);
  DLSLAM_CHECK_GT(guided_search_radius, 0.0);
  DLSLAM_CHECK_GE(min_inliers, 3);
  pose.Check();
}

LoopDetector::LoopDetector(const LoopDetectorOptions& options, const Map* map, const place::KeyFrameIndex* index)
    : options_(options), map_(map), index_(index), consistency_(options.min_consistency) {
  options_.Check();
  DLSLAM_CHECK(map_ != nullptr && index_ != nullptr);
}

void LoopDetector::LoopClosedAt(KeyFrameId keyframe) {
  last_loop_ = keyframe;
  keyframes_since_loop_ = 0;
  consistency_.Reset();
}

LoopDetection LoopDetector::Process(KeyFrameId keyframe) {
  LoopDetection detection;
  ++keyframes_since_loop_;
  const bool map_too_small = map_->NumKeyFrames() <= static_cast<std::size_t>(options_.min_keyframes_between_loops);
  const bool loop_too_recent = last_loop_ != kNoId && keyframes_since_loop_ < options_.min_keyframes_between_loops;
  if (map_too_small || loop_too_recent) {
    detection.outcome = LoopOutcome::kTooEarly;
    return detection;
  }
  const std::optional<KeyFrameSnapshot> current = map_->GetKeyFrame(keyframe);
  const std::optional<place::BowVector> bow = index_->database().Find(keyframe);
  const std::optional<place::FeatureVector> features = index_->Features(keyframe);
  if (!current || !bow || !features) return detection;  // culled meanwhile

  const std::vector<KeyFrameId> connected = map_->BestCovisible(keyframe, kAllNeighbours);
  const double min_score = place::MinScore(index_->database(), *bow, connected);
  const place::CovisibleNeighbours covisible = [this](KeyFrameId id, int count) {
    return map_->BestCovisible(id, static_cast<std::size_t>(std::max(count, 0)));
  };
  const std::vector<place::PlaceCandidate> candidates = place::DetectLoopCandidates(
      index_->database(), keyframe, *bow, connected, min_score, covisible, options_.candidates);
  detection.candidates = static_cast<int>(candidates.size());

  std::vector<place::CandidateGroup> groups;
  // Loops close within one map; joining a new map to an older one is the
  // tracker's merge (it relocalizes in the older maps), done before any
  // pose graph would have to move a map's anchor.
  const KeyFrameId origin = map_->MapOrigin(keyframe);
  for (const place::PlaceCandidate& c : candidates) {
    if (map_->MapOrigin(c.keyframe) != origin) continue;
    place::CandidateGroup group{c.keyframe, map_->BestCovisible(c.keyframe, kAllNeighbours)};
    group.group.push_back(c.keyframe);
    groups.push_back(std::move(group));
  }
  const std::vector<KeyFrameId> accepted = consistency_.Update(groups);
  if (candidates.empty()) return detection;
  if (accepted.empty()) {
    detection.outcome = LoopOutcome::kNotConsistent;
    return detection;
  }
  detection.outcome = LoopOutcome::kRejected;
  for (KeyFrameId candidate : accepted) {
    ++detection.verified;
    detection.match = Verify(*current, *features, candidate);
    if (detection.match) {
      detection.outcome = LoopOutcome::kFound;
      break;
    }
  }
  return detection;
}

std::optional<LoopMatch> LoopDetector::Verify(const KeyFrameSnapshot& current, const place::FeatureVector& features,
                                              KeyFrameId candidate) const {
  const std::optional<KeyFrameSnapshot> loop = map_->GetKeyFrame(candidate);
  const std::optional<place::FeatureVector> loop_features = index_->Features(candidate);
  if (!loop || !loop_features) return std::nullopt;
  const Frame& frame = *current.frame;
  const std::vector<MapPointId> bow_matches =
      place::MatchByBow(frame, features, *loop->frame, *loop_features, loop->points, options_.bow_match);
  // Why a candidate fails, at debug level (`dlslam -v run ...`).
  const auto reject = [&](const char* why, int count) {
    spdlog::debug("loop candidate {} for keyframe {} rejected: {} ({})", candidate, current.id, why, count);
    return std::nullopt;
  };
  if (CountMatches(bow_matches) < options_.min_bow_matches) return reject("bow matches", CountMatches(bow_matches));

  // 3D-3D: the keyframe's own point for the keypoint (or its depth) against
  // the loop side's point.
  const std::vector<MapPointView> loop_points = map_->GetPoints(MatchedIds(bow_matches));
  const auto loop_position = Positions(loop_points);
  const auto own_position = Positions(map_->GetPoints(MatchedIds(current.points)));
  const SE3d world_from_cam = current.cam_from_world.Inverse();
  std::vector<Eigen::Vector3d> a, b;
  std::vector<double> max_error;
  std::vector<int> keypoint_of;
  for (std::size_t i = 0; i < bow_matches.size(); ++i) {
    const auto it_loop = loop_position.find(bow_matches[i]);
    if (it_loop == loop_position.end()) continue;
    std::optional<Eigen::Vector3d> p;
    if (const auto it_own = own_position.find(current.points[i]); it_own != own_position.end()) {
      p = it_own->second;
    } else if (const auto in_camera = frame.Unproject(i)) {
      p = world_from_cam * *in_camera;
    }
    if (!p) continue;
    const double z = std::max((current.cam_from_world * *p).z(), 0.0);
    a.push_back(*p);
    b.push_back(it_loop->second);
    max_error.push_back(options_.ransac_error_m + options_.ransac_error_per_m2 * z * z);
    keypoint_of.push_back(static_cast<int>(i));
  }
  if (static_cast<int>(a.size()) < options_.min_bow_matches) return reject("3D-3D pairs", static_cast<int>(a.size()));
  const std::optional<RigidRansacResult> fit =
      EstimateRigidRansac(a, b, max_error, options_.ransac, options_.seed + static_cast<std::uint32_t>(current.id));
  if (!fit) return reject("no RANSAC consensus of 3D-3D pairs", static_cast<int>(a.size()));

  // b_from_a maps the keyframe's (drifted) world into the loop side's.
  SE3d pose = current.cam_from_world * fit->b_from_a.Inverse();
  std::vector<MapPointId> matches(frame.size(), kNoId);
  for (std::size_t j = 0; j < keypoint_of.size(); ++j) {
    if (fit->inliers[j]) matches[keypoint_of[j]] = bow_matches[keypoint_of[j]];
  }
  if (const int first = OptimizeAndPrune(frame, loop_points, options_.pose, &pose, &matches);
      first < options_.ransac.min_inliers / 2) {
    return reject("inliers of the first pose optimisation", first);
  }

  // More matches from the loop side's neighbourhood, seen with the new pose.
  std::vector<MapPointId> group_ids;
  for (const KeyFrameSnapshot& k :
       map_->GetCovisibleKeyFrames(candidate, static_cast<std::size_t>(options_.loop_group_keyframes))) {
    for (MapPointId id : k.points) {
      if (id != kNoId) group_ids.push_back(id);
    }
  }
  std::sort(group_ids.begin(), group_ids.end());
  group_ids.erase(std::unique(group_ids.begin(), group_ids.end()), group_ids.end());
  std::vector<MapPointId> matched = MatchedIds(matches);
  std::sort(matched.begin(), matched.end());
  std::vector<MapPointId> unmatched_ids;
  std::set_difference(group_ids.begin(), group_ids.end(), matched.begin(), matched.end(),
                      std::back_inserter(unmatched_ids));
  ProjectionMatchOptions search;
  search.radius = options_.guided_search_radius;
  SearchByProjection(frame, pose, map_->GetPoints(unmatched_ids), search, &matches);
  const int inliers = OptimizeAndPrune(frame, map_->GetPoints(MatchedIds(matches)), options_.pose, &pose, &matches);
  if (inliers < options_.min_inliers) return reject("inliers after the guided search", inliers);
  return LoopMatch{current.id, candidate, pose, std::move(matches), inliers};
}

}  // namespace dlslam

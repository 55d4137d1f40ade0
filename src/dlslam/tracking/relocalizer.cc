#include "dlslam/tracking/relocalizer.h"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <unordered_map>

#include "dlslam/tracking/matched_pose.h"
#include "dlslam/util/check.h"

namespace dlslam {

void RelocalizerOptions::Check() const {
  DLSLAM_CHECK_GE(min_bow_matches, 4, "min_bow_matches (PnP needs 4)");
  bow_match.Check();
  DLSLAM_CHECK_GT(ransac_reprojection_px, 0.0);
  DLSLAM_CHECK_GT(ransac_iterations, 0);
  DLSLAM_CHECK_GE(min_first_inliers, 3);
  DLSLAM_CHECK_GT(guided_search_radius, 0.0);
  DLSLAM_CHECK_GE(local_keyframes, 1);
  DLSLAM_CHECK_GE(min_inliers, min_first_inliers, "min_inliers below min_first_inliers");
  DLSLAM_CHECK_GE(max_candidates, 1);
  candidates.Check();
  pose.Check();
}

Relocalizer::Relocalizer(const RelocalizerOptions& options, const Map* map, const place::KeyFrameIndex* index)
    : options_(options), map_(map), index_(index) {
  options_.Check();
  DLSLAM_CHECK(map_ != nullptr && index_ != nullptr);
}

RelocalizationAttempt Relocalizer::Relocalize(const Frame& frame, KeyFrameId below) const {
  RelocalizationAttempt attempt;
  if (frame.size() == 0 || index_->size() == 0) return attempt;
  const place::BowDescription description = index_->Describe(frame.descriptors());
  const place::CovisibleNeighbours covisible = [this](KeyFrameId id, int count) {
    return map_->BestCovisible(id, static_cast<std::size_t>(std::max(count, 0)));
  };
  std::vector<KeyFrameId> excluded;
  if (below != kNoId) {
    for (const KeyFramePose& k : map_->KeyFramePoses()) {
      if (k.id >= below) excluded.push_back(k.id);
    }
  }
  const std::vector<place::PlaceCandidate> candidates = place::DetectRelocalizationCandidates(
      index_->database(), description.bow, covisible, options_.candidates, std::move(excluded));
  attempt.candidates = static_cast<int>(candidates.size());
  const int n = std::min(static_cast<int>(candidates.size()), options_.max_candidates);
  for (int c = 0; c < n; ++c) {
    bool tried = false;
    attempt.result = TryCandidate(frame, description.features, candidates[c].keyframe, &tried);
    attempt.tried += tried;
    if (attempt.result) break;
  }
  return attempt;
}

std::optional<Relocalization> Relocalizer::TryCandidate(const Frame& frame, const place::FeatureVector& frame_features,
                                                        KeyFrameId candidate, bool* tried) const {
  const std::optional<KeyFrameSnapshot> keyframe = map_->GetKeyFrame(candidate);
  const std::optional<place::FeatureVector> keyframe_features = index_->Features(candidate);
  if (!keyframe || !keyframe_features) return std::nullopt;  // culled meanwhile
  std::vector<MapPointId> matches =
      place::MatchByBow(frame, frame_features, *keyframe->frame, *keyframe_features, keyframe->points, options_.bow_match);
  if (CountMatches(matches) < options_.min_bow_matches) return std::nullopt;
  *tried = true;

  // PnP RANSAC on the undistorted keypoints (the frame's camera has no
  // distortion left for them).
  const std::vector<MapPointView> points = map_->GetPoints(MatchedIds(matches));
  std::unordered_map<MapPointId, Eigen::Vector3d> position;
  for (const MapPointView& p : points) position[p.id] = p.position;
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  std::vector<int> keypoint_of;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const auto it = position.find(matches[i]);
    if (it == position.end()) continue;
    object.emplace_back(static_cast<float>(it->second.x()), static_cast<float>(it->second.y()),
                        static_cast<float>(it->second.z()));
    image.emplace_back(static_cast<float>(frame.keypoint(i).uv.x()), static_cast<float>(frame.keypoint(i).uv.y()));
    keypoint_of.push_back(static_cast<int>(i));
  }
  if (static_cast<int>(object.size()) < options_.min_bow_matches) return std::nullopt;
  const CameraIntrinsics& camera = frame.camera();
  const cv::Matx33d k(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  cv::Mat rvec, tvec;
  std::vector<int> ransac_inliers;
  const bool solved =
      cv::solvePnPRansac(object, image, k, cv::noArray(), rvec, tvec, false, options_.ransac_iterations,
                         static_cast<float>(options_.ransac_reprojection_px), 0.99, ransac_inliers, cv::SOLVEPNP_P3P);
  if (!solved || static_cast<int>(ransac_inliers.size()) < options_.min_first_inliers) return std::nullopt;
  const Eigen::Vector3d rotation_vector(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2));
  SE3d pose(SO3d::Exp(rotation_vector), Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
  // Only RANSAC's inliers go into the first optimisation.
  std::vector<MapPointId> inlier_matches(frame.size(), kNoId);
  for (int j : ransac_inliers) inlier_matches[keypoint_of[j]] = matches[keypoint_of[j]];
  int inliers = OptimizeAndPrune(frame, points, options_.pose, &pose, &inlier_matches);
  if (inliers < options_.min_first_inliers) return std::nullopt;

  // More points: the candidate's local map, projected with the new pose.
  for (const double radius : {options_.guided_search_radius, options_.guided_search_radius / 3}) {
    if (inliers >= options_.min_inliers) break;
    const LocalMapSnapshot local =
        map_->GetLocalMap(MatchedIds(inlier_matches), static_cast<std::size_t>(options_.local_keyframes));
    ProjectionMatchOptions search;
    search.radius = radius;
    search.ratio = 0.9;
    search.max_distance = 100;
    std::vector<MapPointId> matched = MatchedIds(inlier_matches);
    std::sort(matched.begin(), matched.end());
    std::vector<MapPointView> unmatched;
    for (const MapPointView& p : local.points) {
      if (!std::binary_search(matched.begin(), matched.end(), p.id)) unmatched.push_back(p);
    }
    SearchByProjection(frame, pose, unmatched, search, &inlier_matches);
    inliers = OptimizeAndPrune(frame, map_->GetPoints(MatchedIds(inlier_matches)), options_.pose, &pose,
                               &inlier_matches);
  }
  if (inliers < options_.min_inliers) return std::nullopt;
  return Relocalization{pose, std::move(inlier_matches), candidate, inliers};
}

}  // namespace dlslam

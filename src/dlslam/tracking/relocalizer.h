#pragma once
// Relocalization of a lost frame against the map (ORB-SLAM's scheme, written
// by us): bag-of-words candidates from the keyframe index; per candidate,
// matches to its map points through the direct index; a first pose by PnP
// with RANSAC on the 2D keypoints; the pose optimisation; a guided
// projection search of the candidate's local map for more points; accepted
// only with many inliers, because a wrong relocalization corrupts the map.
//
// Why PnP on 2D keypoints (cv::solvePnPRansac, P3P minimal sets) and not a
// 3D-3D Horn fit on the frame's depth: relocalization happens exactly when
// the camera sees something hard (far walls, glancing views, missing
// depth); PnP uses every matched keypoint, depth or not, and the pose
// optimisation that follows uses the depth where there is some (the RGB-D
// residual), so the depth is not lost, only not required.

#include <optional>
#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/map/map.h"
#include "dlslam/match/projection_matcher.h"
#include "dlslam/optimize/pose_optimizer.h"
#include "dlslam/place/bow_matcher.h"
#include "dlslam/place/keyframe_index.h"
#include "dlslam/place/place_candidates.h"

namespace dlslam {

struct RelocalizerOptions {
  // Bag-of-words matches a candidate needs before RANSAC [count] (ORB-SLAM: 15).
  int min_bow_matches = 15;
  place::BowMatchOptions bow_match;
  // RANSAC reprojection threshold [px at level 0] and iterations [count].
  double ransac_reprojection_px = 4.0;
  int ransac_iterations = 200;
  // Inliers of the first pose optimisation needed to go on with a candidate [count].
  int min_first_inliers = 10;
  // Radius of the guided projection search [px at level 0] (ORB-SLAM: 10).
  double guided_search_radius = 10.0;
  // Keyframes of the candidate's local map searched by projection [count].
  int local_keyframes = 10;
  // Inliers needed to accept a relocalization [count] (ORB-SLAM: 50).
  int min_inliers = 50;
  // Candidates tried per frame, best first [count].
  int max_candidates = 10;
  place::CandidateOptions candidates;
  PoseOptimizerOptions pose;
  void Check() const;  // throws dlslam::Error with the values
};

struct Relocalization {
  SE3d cam_from_world;
  std::vector<MapPointId> matches;  // per frame keypoint, the inlier points
  KeyFrameId keyframe = kNoId;      // the candidate that gave the pose
  int inliers = 0;
};

struct RelocalizationAttempt {
  std::optional<Relocalization> result;
  int candidates = 0;  // candidates from the database
  int tried = 0;       // candidates that reached RANSAC
};

class Relocalizer {
 public:
  // `map` and `index` outlive the relocalizer.
  Relocalizer(const RelocalizerOptions& options, const Map* map, const place::KeyFrameIndex* index);

  // Candidates among the keyframes with an id below `below` only (kNoId:
  // all): the maps older than a new one, to merge it (tracker.h).
  RelocalizationAttempt Relocalize(const Frame& frame, KeyFrameId below = kNoId) const;

 private:
  // The pose from one candidate keyframe, or nullopt.
  std::optional<Relocalization> TryCandidate(const Frame& frame, const place::FeatureVector& frame_features,
                                             KeyFrameId candidate, bool* tried) const;

  RelocalizerOptions options_;
  const Map* map_;
  const place::KeyFrameIndex* index_;
};

}  // namespace dlslam

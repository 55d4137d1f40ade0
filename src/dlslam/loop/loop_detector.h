#pragma once
// Finding a loop for a new keyframe and checking it geometrically (ORB-SLAM's
// DetectLoop + ComputeSim3 for RGB-D, written by us):
//   1. bag-of-words candidates that look at least as similar as the
//      keyframe's own covisible neighbours (place_candidates.h);
//   2. temporal consistency: the candidate's group must have been found for
//      `min_consistency` keyframes in a row (consistency_checker.h);
//   3. matches by the direct index, then an SE(3) from 3D-3D correspondences
//      with RANSAC (RGB-D: the scale is known);
//   4. with that pose, the loop keyframe's neighbourhood is projected into the
//      keyframe for more matches and the pose optimised; accepted only with
//      many inliers, because a false loop wrecks the map.
// It reads the map and the keyframe index, never writes them.

#include <optional>
#include <vector>

#include "dlslam/map/map.h"
#include "dlslam/match/projection_matcher.h"
#include "dlslam/optimize/pose_optimizer.h"
#include "dlslam/optimize/rigid_ransac.h"
#include "dlslam/place/bow_matcher.h"
#include "dlslam/place/consistency_checker.h"
#include "dlslam/place/keyframe_index.h"
#include "dlslam/place/place_candidates.h"

namespace dlslam {

struct LoopDetectorOptions {
  // Keyframes in the map before loops are looked for, and keyframes after a
  // closed loop before the next one [count] (ORB-SLAM: 10).
  int min_keyframes_between_loops = 10;
  // Successive keyframes that must find a candidate's group [count] (ORB-SLAM: 3).
  int min_consistency = 3;
  place::CandidateOptions candidates;
  // Direct-index matches a candidate needs before RANSAC [count] (ORB-SLAM: 20).
  int min_bow_matches = 20;
  place::BowMatchOptions bow_match;
  // RANSAC on 3D-3D matches; inlier when the aligned points are closer than
  // ransac_error_m + ransac_error_per_m2 * z^2 (z: depth in the keyframe [m]),
  // Kinect depth noise growing with the square of the depth.
  RigidRansacOptions ransac;
  double ransac_error_m = 0.03;
  double ransac_error_per_m2 = 0.01;
  // Keyframes of the loop side projected for more matches: the candidate and
  // its best covisible neighbours [count].
  int loop_group_keyframes = 10;
  // Radius of that projection search [px at level 0] (ORB-SLAM: 10).
  double guided_search_radius = 10.0;
  // Inliers of the final pose optimisation needed to accept a loop [count].
  int min_inliers = 50;
  PoseOptimizerOptions pose;
  std::uint32_t seed = 1;  // RANSAC's, so that runs repeat

  void Check() const;  // throws dlslam::Error with the values
};

// A verified loop: keyframe `current` sees the place of keyframe `loop`.
struct LoopMatch {
  KeyFrameId current = kNoId;
  KeyFrameId loop = kNoId;
  // Pose of `current` in the loop side's (older, less drifted) frame.
  SE3d corrected_cam_from_world;
  // Per keypoint of `current`: the loop side's point it sees, kNoId if none.
  std::vector<MapPointId> matches;
  int inliers = 0;
};

// Why a keyframe gave no loop, for the statistics.
enum class LoopOutcome { kTooEarly, kNoCandidate, kNotConsistent, kRejected, kFound };

struct LoopDetection {
  LoopOutcome outcome = LoopOutcome::kNoCandidate;
  std::optional<LoopMatch> match;
  int candidates = 0;  // bag-of-words candidates
  int verified = 0;    // consistent candidates that reached RANSAC
};

class LoopDetector {
 public:
  // `map` and `index` outlive the detector.
  LoopDetector(const LoopDetectorOptions& options, const Map* map, const place::KeyFrameIndex* index);

  // Looks for a loop of `keyframe` (already in the index). Call once per
  // keyframe, in order: the consistency test carries state across calls.
  LoopDetection Process(KeyFrameId keyframe);

  // A loop was closed at `keyframe`: wait min_keyframes_between_loops.
  void LoopClosedAt(KeyFrameId keyframe);

 private:
  std::optional<LoopMatch> Verify(const KeyFrameSnapshot& current, const place::FeatureVector& features,
                                  KeyFrameId candidate) const;

  LoopDetectorOptions options_;
  const Map* map_;
  const place::KeyFrameIndex* index_;
  place::ConsistencyChecker consistency_;
  KeyFrameId last_loop_ = kNoId;
  int keyframes_since_loop_ = 0;
};

}  // namespace dlslam

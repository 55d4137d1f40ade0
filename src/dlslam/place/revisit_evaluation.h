#pragma once
// Does place recognition find revisits? A query is a frame with a revisit:
// a frame at least `min_frame_gap` frames away whose camera is within
// `max_distance_m` and `max_angle_deg` of it. Its best-scoring frame among
// all frames at least `min_frame_gap` away is correct when it is within
// `accept_distance_m` and `accept_angle_deg` (a looser tolerance: a frame
// 0.35 m beside a revisit sees the same place; camera distance is only a
// proxy for view overlap). precision@1 = correct / queries; `chance` is the
// expected precision of a random pick among the same frames.

#include <vector>

#include "dlslam/geometry/se3.h"
#include "dlslam/place/bow_vector.h"

namespace dlslam::place {

struct RevisitCriteria {
  int min_frame_gap = 100;       // frames closer in time are never compared [frames]
  double max_distance_m = 0.3;   // camera centres at most this far apart [m]
  double max_angle_deg = 20.0;   // relative rotation at most this [deg]
  double accept_distance_m = 0.5;  // a best match this near counts as correct [m], >= max_distance_m
  double accept_angle_deg = 30.0;  // ... and this little rotated [deg], >= max_angle_deg
  void Check() const;            // throws dlslam::Error with the values
};

struct RevisitFrame {
  int index = 0;        // frame number in the sequence (for the time gap)
  SE3d world_from_cam;  // ground truth
  BowVector bow;
};

struct RevisitEvaluation {
  int queries = 0;  // frames that have a revisit
  int correct = 0;  // ... whose best match is one
  double precision_at_1 = 0.0;
  double chance = 0.0;
};

RevisitEvaluation EvaluateRevisits(const std::vector<RevisitFrame>& frames, const RevisitCriteria& criteria = {});

}  // namespace dlslam::place

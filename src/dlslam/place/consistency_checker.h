#pragma once
// Temporal consistency of loop candidates (ORB-SLAM's scheme, written by us):
// a candidate's group is the candidate and its covisible keyframes. A group
// that overlaps (shares a keyframe with) a group kept at the previous query
// continues it, one step more consistent; other groups start at 0. A
// candidate is accepted once its group has been consistent for
// `min_consistency` successive queries, i.e. it was seen at
// min_consistency + 1 successive keyframes.
//
//   ConsistencyChecker checker(3);
//   for each new keyframe:
//     accepted = checker.Update(groups of its loop candidates);

#include <vector>

#include "dlslam/map/map_types.h"

namespace dlslam::place {

struct CandidateGroup {
  KeyFrameId candidate = kNoId;
  std::vector<KeyFrameId> group;  // the candidate and its covisible keyframes (any order)
};

struct ConsistentGroup {
  std::vector<KeyFrameId> keyframes;  // sorted
  int consistency = 0;                // successive queries it has been seen at, minus 1
};

class ConsistencyChecker {
 public:
  // Throws dlslam::Error unless min_consistency >= 1.
  explicit ConsistencyChecker(int min_consistency = 3);

  // One query's candidates; returns the accepted ones (each at most once, in
  // the given order). No candidates clear the history.
  std::vector<KeyFrameId> Update(const std::vector<CandidateGroup>& candidates);
  void Reset() { groups_.clear(); }

  const std::vector<ConsistentGroup>& groups() const { return groups_; }
  int min_consistency() const { return min_consistency_; }

 private:
  int min_consistency_;
  std::vector<ConsistentGroup> groups_;
};

}  // namespace dlslam::place

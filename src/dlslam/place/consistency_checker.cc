#include "dlslam/place/consistency_checker.h"

#include <algorithm>

#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

bool Overlap(const std::vector<KeyFrameId>& a, const std::vector<KeyFrameId>& b) {
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() && ib != b.end()) {
    if (*ia < *ib) {
      ++ia;
    } else if (*ib < *ia) {
      ++ib;
    } else {
      return true;
    }
  }
  return false;
}

}  // namespace

ConsistencyChecker::ConsistencyChecker(int min_consistency) : min_consistency_(min_consistency) {
  DLSLAM_CHECK_GE(min_consistency, 1, "loop consistency needs at least one previous query");
}

std::vector<KeyFrameId> ConsistencyChecker::Update(const std::vector<CandidateGroup>& candidates) {
  std::vector<KeyFrameId> accepted;
  std::vector<ConsistentGroup> next;
  // A previous group is continued by at most one new group, so one long
  // streak cannot fan out into several.
  std::vector<bool> continued(groups_.size(), false);
  for (const CandidateGroup& candidate : candidates) {
    std::vector<KeyFrameId> group = candidate.group;
    group.push_back(candidate.candidate);
    std::sort(group.begin(), group.end());
    group.erase(std::unique(group.begin(), group.end()), group.end());

    bool continues_some = false;
    bool is_accepted = false;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      if (!Overlap(group, groups_[g].keyframes)) continue;
      continues_some = true;
      const int consistency = groups_[g].consistency + 1;
      if (!continued[g]) {
        next.push_back({group, consistency});
        continued[g] = true;
      }
      if (consistency >= min_consistency_ && !is_accepted) {
        is_accepted = true;
        if (std::find(accepted.begin(), accepted.end(), candidate.candidate) == accepted.end()) {
          accepted.push_back(candidate.candidate);
        }
      }
    }
    if (!continues_some) next.push_back({std::move(group), 0});
  }
  groups_ = std::move(next);
  return accepted;
}

}  // namespace dlslam::place

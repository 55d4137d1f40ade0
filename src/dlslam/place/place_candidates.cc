#include "dlslam/place/place_candidates.h"

#include <algorithm>
#include <unordered_map>

#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

std::vector<PlaceCandidate> Detect(const KeyFrameDatabase& database, const BowVector& query,
                                   std::vector<KeyFrameId> excluded, double min_score,
                                   const CovisibleNeighbours& covisible, const CandidateOptions& options) {
  options.Check();
  const std::vector<SharedWords> sharing = database.KeyFramesSharingWords(query, std::move(excluded));
  if (sharing.empty()) return {};
  int most_common = 0;
  for (const SharedWords& s : sharing) most_common = std::max(most_common, s.common_words);
  const double min_common = options.min_common_words_ratio * most_common;

  std::vector<KeyFrameId> ids;
  for (const SharedWords& s : sharing) {
    if (s.common_words > min_common || s.common_words == most_common) ids.push_back(s.keyframe);
  }
  const std::vector<double> scores = database.Scores(query, ids);
  // Every keyframe with enough shared words is scored and counts in the
  // groups; only those reaching min_score start a group.
  std::unordered_map<KeyFrameId, double> score_of;
  for (std::size_t i = 0; i < ids.size(); ++i) score_of[ids[i]] = scores[i];

  std::vector<PlaceCandidate> groups;
  double best_group_score = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (scores[i] < min_score) continue;
    PlaceCandidate group{ids[i], scores[i], scores[i]};
    for (KeyFrameId neighbour : covisible(ids[i], options.group_size)) {
      auto it = score_of.find(neighbour);
      if (it == score_of.end() || neighbour == ids[i]) continue;
      group.group_score += it->second;
      if (it->second > group.score) {
        group.score = it->second;
        group.keyframe = neighbour;
      }
    }
    best_group_score = std::max(best_group_score, group.group_score);
    groups.push_back(group);
  }

  const double retain = options.retain_ratio * best_group_score;
  std::vector<PlaceCandidate> out;
  for (const PlaceCandidate& group : groups) {
    if (group.group_score < retain) continue;
    // Groups overlap: the same best keyframe may lead several; keep its best group.
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const PlaceCandidate& c) { return c.keyframe == group.keyframe; });
    if (it == out.end()) {
      out.push_back(group);
    } else if (group.group_score > it->group_score) {
      *it = group;
    }
  }
  std::sort(out.begin(), out.end(), [](const PlaceCandidate& a, const PlaceCandidate& b) {
    return a.group_score != b.group_score ? a.group_score > b.group_score : a.keyframe < b.keyframe;
  });
  return out;
}

}  // namespace

void CandidateOptions::Check() const {
  DLSLAM_CHECK(min_common_words_ratio >= 0.0 && min_common_words_ratio <= 1.0,
               "min_common_words_ratio must be in [0, 1], got {}", min_common_words_ratio);
  DLSLAM_CHECK_GE(group_size, 0, "group_size must be >= 0");
  DLSLAM_CHECK(retain_ratio >= 0.0 && retain_ratio <= 1.0, "retain_ratio must be in [0, 1], got {}", retain_ratio);
}

double MinScore(const KeyFrameDatabase& database, const BowVector& query, const std::vector<KeyFrameId>& neighbours) {
  double lowest = 1.0;
  std::vector<KeyFrameId> stored;
  for (KeyFrameId id : neighbours) {
    if (database.Contains(id)) stored.push_back(id);
  }
  for (double score : database.Scores(query, stored)) lowest = std::min(lowest, score);
  return lowest;
}

std::vector<PlaceCandidate> DetectLoopCandidates(const KeyFrameDatabase& database, KeyFrameId query_id,
                                                 const BowVector& query, const std::vector<KeyFrameId>& connected,
                                                 double min_score, const CovisibleNeighbours& covisible,
                                                 const CandidateOptions& options) {
  std::vector<KeyFrameId> excluded = connected;
  excluded.push_back(query_id);
  return Detect(database, query, std::move(excluded), min_score, covisible, options);
}

std::vector<PlaceCandidate> DetectRelocalizationCandidates(const KeyFrameDatabase& database, const BowVector& query,
                                                           const CovisibleNeighbours& covisible,
                                                           const CandidateOptions& options,
                                                           std::vector<KeyFrameId> excluded) {
  return Detect(database, query, std::move(excluded), 0.0, covisible, options);
}

}  // namespace dlslam::place

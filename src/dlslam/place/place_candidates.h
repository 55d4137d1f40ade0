#pragma once
// Loop and relocalization candidates from the keyframe database, by the
// scheme of ORB-SLAM (Mur-Artal & Tardos), written by us:
//  1. keyframes sharing words with the query; keep those sharing more than
//     `min_common_words_ratio` x the most any keyframe shares;
//  2. score them (L1); a loop candidate must also reach `min_score`: the
//     query's lowest score against its own covisible keyframes (MinScore);
//  3. group each candidate with its best covisible neighbours and add up the
//     scores of the group's scored members; keep, per group above
//     `retain_ratio` x the best group score, its best-scoring keyframe.
// The map is not touched: the covisibility comes in as a function over ids,
// so the loop-closing thread and relocalization can call these with the
// map's data (and tests with plain tables).

#include <functional>
#include <vector>

#include "dlslam/map/map_types.h"
#include "dlslam/place/keyframe_database.h"

namespace dlslam::place {

struct CandidateOptions {
  // Keep keyframes sharing more than this fraction of the best keyframe's
  // shared-word count [fraction, 0..1]
  double min_common_words_ratio = 0.8;
  // Covisible neighbours that form a candidate's group [count, >= 0]
  int group_size = 10;
  // Keep groups whose accumulated score reaches this fraction of the best
  // group's [fraction, 0..1]
  double retain_ratio = 0.75;
  void Check() const;  // throws dlslam::Error with the values
};

struct PlaceCandidate {
  KeyFrameId keyframe = kNoId;  // best-scoring keyframe of its group
  double score = 0.0;           // its L1 score against the query
  double group_score = 0.0;     // accumulated over the group it was found in
};

// The up-to-`count` covisible keyframes of `keyframe`, most shared points first.
using CovisibleNeighbours = std::function<std::vector<KeyFrameId>(KeyFrameId keyframe, int count)>;

// Lowest L1 score of `query` against `neighbours` stored in `database`
// (ORB-SLAM's loop threshold: a loop must look at least as similar as the
// least similar covisible keyframe). 1 when none is stored: nothing passes.
double MinScore(const KeyFrameDatabase& database, const BowVector& query, const std::vector<KeyFrameId>& neighbours);

// Loop candidates for keyframe `query_id` with vector `query`; `connected`
// (its covisible keyframes) and the query itself are never candidates.
// Sorted by group score, best first.
std::vector<PlaceCandidate> DetectLoopCandidates(const KeyFrameDatabase& database, KeyFrameId query_id,
                                                 const BowVector& query, const std::vector<KeyFrameId>& connected,
                                                 double min_score, const CovisibleNeighbours& covisible,
                                                 const CandidateOptions& options = {});

// Relocalization candidates for a lost frame: the same without the
// connected-keyframe exclusion and without a minimum score; `excluded`
// keyframes neither count nor lead (the keyframes of a map that is to be
// merged into the others, when looking for it in them).
std::vector<PlaceCandidate> DetectRelocalizationCandidates(const KeyFrameDatabase& database, const BowVector& query,
                                                           const CovisibleNeighbours& covisible,
                                                           const CandidateOptions& options = {},
                                                           std::vector<KeyFrameId> excluded = {});

}  // namespace dlslam::place

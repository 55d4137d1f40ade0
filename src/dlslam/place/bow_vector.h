#pragma once
// Bag-of-words vectors of an image and their similarity.
//
// A BowVector lists (word, weight) pairs sorted by word, each word once;
// after NormalizeL1 the weights sum to 1. The similarity of two normalised
// vectors is ORB-SLAM's / DBoW2's L1 score
//   s(v, w) = 1 - 0.5 * |v - w|_1   in [0, 1] (1 = identical),
// which for non-negative weights equals sum_i min(v_i, w_i): only the words
// both share contribute, so it is computed by one merge over the two lists.

#include <cstdint>
#include <utility>
#include <vector>

namespace dlslam::place {

using WordId = std::uint32_t;
using NodeId = std::uint32_t;
using WordWeight = float;

struct BowEntry {
  WordId word = 0;
  WordWeight weight = 0;
  bool operator==(const BowEntry&) const = default;
};
using BowVector = std::vector<BowEntry>;  // sorted by word, unique

// Per tree node at the direct-index level: the features (indices into the
// transformed descriptors) whose path went through it. Sorted by node;
// guided matching compares only features that share a node.
struct FeatureNode {
  NodeId node = 0;
  std::vector<std::uint32_t> features;  // ascending
};
using FeatureVector = std::vector<FeatureNode>;

// Sorts by word and merges repeated words (weights added).
void SortAndMerge(BowVector& vector);
// Scales weights to sum 1 (a vector of zeros stays as it is).
void NormalizeL1(BowVector& vector);
// L1 score of two L1-normalised vectors, in [0, 1].
double ScoreL1(const BowVector& a, const BowVector& b);
// Number of words the two vectors share.
int CommonWords(const BowVector& a, const BowVector& b);

}  // namespace dlslam::place

#pragma once
// A vocabulary tree of binary ORB descriptors (as DBoW2's, written by us):
// node 0 is the root; every other node holds a 256-bit centre; the leaves are
// the words, each with an idf weight. A descriptor's word is found by
// descending from the root to the nearest child at each level (k Hamming
// distances per level).
//
//   Vocabulary vocabulary = LoadVocabulary(path);     // vocabulary_file.h
//   BowVector bow; FeatureVector features;
//   vocabulary.Transform(descriptors, bow, features);  // L1-normalised tf-idf
//   double s = ScoreL1(bow, other_bow);
//
// Storage: nodes in breadth-first order, the children of a node contiguous,
// so the tree is fully described by each node's child count; words are the
// leaves numbered in node order.

#include <opencv2/core.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "dlslam/map/map_types.h"
#include "dlslam/place/bow_vector.h"

namespace dlslam::place {

inline constexpr WordId kNoWord = 0xFFFFFFFFu;

class Vocabulary {
 public:
  Vocabulary() = default;  // empty: Transform gives empty vectors

  // `child_counts[i]`: children of node i (breadth-first order, node 0 the
  // root, children contiguous); `centres[i]`: node i's centre (the root's is
  // unused); `word_weights[w]`: idf weight of the w-th leaf. Throws
  // dlslam::Error when the parts do not describe a tree with at most
  // `branching` children per node and `levels` levels below the root, or
  // the counts disagree (the file reader checks first, naming the file).
  Vocabulary(int branching, int levels, std::vector<Descriptor> centres, std::vector<std::uint8_t> child_counts,
             std::vector<WordWeight> word_weights);

  bool empty() const { return word_weights_.empty(); }
  int branching() const { return branching_; }  // k
  int levels() const { return levels_; }        // L (tree depth below the root)
  std::size_t node_count() const { return child_counts_.size(); }
  std::size_t word_count() const { return word_weights_.size(); }

  // The word of one descriptor.
  WordId WordOf(const Descriptor& descriptor) const;
  // Word and the ancestor (or the leaf itself, when shallower) at depth
  // `level` below the root.
  WordId WordOf(const Descriptor& descriptor, int level, NodeId& node_at_level) const;

  // tf-idf vector, L1-normalised (weight of a word = idf x occurrences).
  BowVector Transform(std::span<const Descriptor> descriptors) const;
  // The same, plus the direct index: features grouped by their node at
  // `direct_index_level` (1..levels; ORB-SLAM uses 2 of 6 for k=10, i.e. 100
  // groups). Throws dlslam::Error for a level outside 1..levels.
  void Transform(std::span<const Descriptor> descriptors, int direct_index_level, BowVector& bow,
                 FeatureVector& features) const;

  // Parts, as given to the constructor (for the file writer).
  const std::vector<Descriptor>& centres() const { return centres_; }
  const std::vector<std::uint8_t>& child_counts() const { return child_counts_; }
  const std::vector<WordWeight>& word_weights() const { return word_weights_; }
  // Word of a node, kNoWord for inner nodes.
  WordId word_of_node(NodeId node) const { return word_of_node_[node]; }
  NodeId first_child(NodeId node) const { return first_child_[node]; }
  int depth_of_node(NodeId node) const { return depth_[node]; }

 private:
  int branching_ = 0;
  int levels_ = 0;
  std::vector<Descriptor> centres_;
  std::vector<std::uint8_t> child_counts_;
  std::vector<WordWeight> word_weights_;
  // Derived on construction.
  std::vector<NodeId> first_child_;
  std::vector<WordId> word_of_node_;
  std::vector<std::uint8_t> depth_;
};

// Rows of a CV_8UC1 n x 32 matrix (OrbFeatures::descriptors) as descriptors;
// throws dlslam::Error for another type or width.
std::vector<Descriptor> DescriptorsFromMat(const cv::Mat& rows);

}  // namespace dlslam::place

#include "dlslam/place/vocabulary.h"

#include <algorithm>
#include <cstring>

#include "dlslam/util/check.h"

namespace dlslam::place {

Vocabulary::Vocabulary(int branching, int levels, std::vector<Descriptor> centres,
                       std::vector<std::uint8_t> child_counts, std::vector<WordWeight> word_weights)
    : branching_(branching),
      levels_(levels),
      centres_(std::move(centres)),
      child_counts_(std::move(child_counts)),
      word_weights_(std::move(word_weights)) {
  DLSLAM_CHECK(branching_ >= 2 && branching_ <= 255, "vocabulary: branching factor {} not in [2, 255]",
               branching_);
  DLSLAM_CHECK(levels_ >= 1 && levels_ <= 16, "vocabulary: levels {} not in [1, 16]", levels_);
  const std::size_t n = child_counts_.size();
  DLSLAM_CHECK_GE(n, std::size_t{2}, "vocabulary: a tree needs a root and at least one word");
  DLSLAM_CHECK_EQ(centres_.size(), n, "vocabulary: one centre per node");
  first_child_.assign(n, 0);
  word_of_node_.assign(n, kNoWord);
  depth_.assign(n, 0);
  // Breadth-first: the children of node i follow those of nodes < i.
  std::size_t next_child = 1;
  WordId words = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int children = child_counts_[i];
    DLSLAM_CHECK_LE(children, branching_, "vocabulary: node {} has too many children", i);
    DLSLAM_CHECK(i == 0 || i < next_child, "vocabulary: node {} is not reachable from the root", i);
    first_child_[i] = static_cast<NodeId>(next_child);
    if (children == 0) {
      DLSLAM_CHECK(i != 0, "vocabulary: the root has no children");
      word_of_node_[i] = words++;
      continue;
    }
    DLSLAM_CHECK_LT(depth_[i], levels_, "vocabulary: node {} is at the last level but has children", i);
    DLSLAM_CHECK_LE(next_child + children, n, "vocabulary: node {} has children past the last node", i);
    for (int c = 0; c < children; ++c) depth_[next_child + c] = static_cast<std::uint8_t>(depth_[i] + 1);
    next_child += children;
  }
  DLSLAM_CHECK_EQ(next_child, n, "vocabulary: child counts must account for every node");
  DLSLAM_CHECK_EQ(static_cast<std::size_t>(words), word_weights_.size(), "vocabulary: one weight per word");
}

WordId Vocabulary::WordOf(const Descriptor& descriptor, int level, NodeId& node_at_level) const {
  NodeId node = 0;
  node_at_level = 0;
  while (child_counts_[node] != 0) {
    const NodeId first = first_child_[node];
    const NodeId end = first + child_counts_[node];
    NodeId best = first;
    int best_distance = HammingDistance(centres_[first].data(), descriptor.data());
    for (NodeId c = first + 1; c < end; ++c) {
      const int distance = HammingDistance(centres_[c].data(), descriptor.data());
      if (distance < best_distance) {
        best_distance = distance;
        best = c;
      }
    }
    node = best;
    if (depth_[node] <= level) node_at_level = node;
  }
  return word_of_node_[node];
}

WordId Vocabulary::WordOf(const Descriptor& descriptor) const {
  if (empty()) return kNoWord;
  NodeId unused;
  return WordOf(descriptor, levels_, unused);
}

BowVector Vocabulary::Transform(std::span<const Descriptor> descriptors) const {
  BowVector bow;
  if (empty()) return bow;
  bow.reserve(descriptors.size());
  NodeId unused;
  for (const Descriptor& d : descriptors) {
    const WordId word = WordOf(d, levels_, unused);
    bow.push_back({word, word_weights_[word]});
  }
  SortAndMerge(bow);
  NormalizeL1(bow);
  return bow;
}

void Vocabulary::Transform(std::span<const Descriptor> descriptors, int direct_index_level, BowVector& bow,
                           FeatureVector& features) const {
  bow.clear();
  features.clear();
  if (empty()) return;
  DLSLAM_CHECK(direct_index_level >= 1 && direct_index_level <= levels_,
               "direct index level {} not in [1, {}]", direct_index_level, levels_);
  bow.reserve(descriptors.size());
  std::vector<std::pair<NodeId, std::uint32_t>> node_feature;
  node_feature.reserve(descriptors.size());
  for (std::uint32_t i = 0; i < descriptors.size(); ++i) {
    NodeId node = 0;
    const WordId word = WordOf(descriptors[i], direct_index_level, node);
    bow.push_back({word, word_weights_[word]});
    node_feature.emplace_back(node, i);
  }
  SortAndMerge(bow);
  NormalizeL1(bow);
  std::sort(node_feature.begin(), node_feature.end());
  for (const auto& [node, feature] : node_feature) {
    if (features.empty() || features.back().node != node) features.push_back({node, {}});
    features.back().features.push_back(feature);
  }
}

std::vector<Descriptor> DescriptorsFromMat(const cv::Mat& rows) {
  if (rows.empty()) return {};
  DLSLAM_CHECK(rows.type() == CV_8UC1 && rows.cols == 32, "descriptors must be CV_8UC1 n x 32, got type {} x {} cols",
               rows.type(), rows.cols);
  std::vector<Descriptor> out(static_cast<std::size_t>(rows.rows));
  for (int r = 0; r < rows.rows; ++r) std::memcpy(out[r].data(), rows.ptr<std::uint8_t>(r), 32);
  return out;
}

}  // namespace dlslam::place

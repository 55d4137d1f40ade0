#pragma once
// Training a vocabulary tree: hierarchical k-means (binary_kmeans.h) from the
// root down to `levels`, then idf weights from the training images:
// idf(w) = ln(N / n_w), N images, n_w of them containing word w.
// Deterministic in the seed whatever the thread count (each node's k-means
// has its own generator, seeded from the training seed and the node's id).

#include <cstdint>
#include <span>
#include <vector>

#include "dlslam/map/map_types.h"
#include "dlslam/place/vocabulary.h"

namespace dlslam::place {

inline constexpr int kMaxVocabularyThreads = 256;

struct VocabularyOptions {
  int branching = 10;       // k: children per node [count, 2..255]
  int levels = 5;           // L: levels below the root [count, 1..16]; up to k^L words
  int max_iterations = 15;  // Lloyd iterations per node, at most [count, >= 1]
  std::uint64_t seed = 0;   // the same seed and data give the same tree
  int threads = 0;          // worker threads [count, 0..256]; 0 = all hardware threads
  void Check() const;       // throws dlslam::Error with the values
};

// Descriptors of the training images, concatenated.
struct TrainingDescriptors {
  std::vector<Descriptor> descriptors;
  std::vector<std::size_t> image_starts;  // image i: [image_starts[i], image_starts[i+1] or end)

  void AddImage(std::span<const Descriptor> image);
  std::size_t image_count() const { return image_starts.size(); }
  std::span<const Descriptor> image(std::size_t i) const;
};

// Throws dlslam::Error when there are no descriptors.
Vocabulary TrainVocabulary(const TrainingDescriptors& training, const VocabularyOptions& options);

// idf weights of `vocabulary`'s words from `training` (the second step of
// TrainVocabulary, exposed to re-weight a tree on other images).
std::vector<WordWeight> ComputeIdfWeights(const Vocabulary& vocabulary, const TrainingDescriptors& training,
                                          int threads);

}  // namespace dlslam::place

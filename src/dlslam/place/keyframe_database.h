#pragma once
// The keyframes' bag-of-words vectors with an inverted index (word ->
// keyframes that contain it), for loop and relocalization queries: a query
// only visits keyframes that share a word with it. Thread-safe (one mutex):
// local mapping adds, loop closing and tracking query.

#include <cstdint>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "dlslam/map/map_types.h"
#include "dlslam/place/bow_vector.h"

namespace dlslam::place {

struct SharedWords {
  KeyFrameId keyframe = kNoId;
  int common_words = 0;
};

class KeyFrameDatabase {
 public:
  // `word_count`: size of the vocabulary (words are < word_count).
  explicit KeyFrameDatabase(std::size_t word_count);

  // Adds or replaces a keyframe's vector. Throws dlslam::Error for a word
  // outside the vocabulary or a vector that is not sorted and unique.
  void Add(KeyFrameId id, BowVector bow);
  // Removes a keyframe; unknown ids are ignored (culled twice is harmless).
  void Erase(KeyFrameId id);
  void Clear();

  std::size_t size() const;
  bool Contains(KeyFrameId id) const;
  std::optional<BowVector> Find(KeyFrameId id) const;

  // Keyframes sharing at least one word with `query`, except those in
  // `excluded` (any order), with the number of shared words; in id order.
  std::vector<SharedWords> KeyFramesSharingWords(const BowVector& query,
                                                 std::vector<KeyFrameId> excluded = {}) const;
  // L1 score of `query` against stored keyframes; unknown ids score 0.
  std::vector<double> Scores(const BowVector& query, const std::vector<KeyFrameId>& ids) const;

 private:
  mutable std::mutex mutex_;
  std::unordered_map<KeyFrameId, BowVector> vectors_;
  std::vector<std::vector<KeyFrameId>> inverted_;  // per word, ascending ids
};

}  // namespace dlslam::place

#include "dlslam/place/keyframe_database.h"

#include <algorithm>

#include "dlslam/util/check.h"

namespace dlslam::place {

KeyFrameDatabase::KeyFrameDatabase(std::size_t word_count) : inverted_(word_count) {}

void KeyFrameDatabase::Add(KeyFrameId id, BowVector bow) {
  for (std::size_t i = 0; i < bow.size(); ++i) {
    DLSLAM_CHECK_LT(bow[i].word, inverted_.size(), "keyframe {}: word outside the vocabulary", id);
    DLSLAM_CHECK(i == 0 || bow[i - 1].word < bow[i].word, "keyframe {}: BoW vector not sorted and unique", id);
  }
  std::lock_guard lock(mutex_);
  if (auto it = vectors_.find(id); it != vectors_.end()) {
    for (const BowEntry& entry : it->second) {
      auto& list = inverted_[entry.word];
      list.erase(std::lower_bound(list.begin(), list.end(), id));
    }
  }
  for (const BowEntry& entry : bow) {
    auto& list = inverted_[entry.word];
    list.insert(std::lower_bound(list.begin(), list.end(), id), id);
  }
  vectors_[id] = std::move(bow);
}

void KeyFrameDatabase::Erase(KeyFrameId id) {
  std::lock_guard lock(mutex_);
  auto it = vectors_.find(id);
  if (it == vectors_.end()) return;
  for (const BowEntry& entry : it->second) {
    auto& list = inverted_[entry.word];
    list.erase(std::lower_bound(list.begin(), list.end(), id));
  }
  vectors_.erase(it);
}

void KeyFrameDatabase::Clear() {
  std::lock_guard lock(mutex_);
  vectors_.clear();
  for (auto& list : inverted_) list.clear();
}

std::size_t KeyFrameDatabase::size() const {
  std::lock_guard lock(mutex_);
  return vectors_.size();
}

bool KeyFrameDatabase::Contains(KeyFrameId id) const {
  std::lock_guard lock(mutex_);
  return vectors_.count(id) > 0;
}

std::optional<BowVector> KeyFrameDatabase::Find(KeyFrameId id) const {
  std::lock_guard lock(mutex_);
  auto it = vectors_.find(id);
  if (it == vectors_.end()) return std::nullopt;
  return it->second;
}

std::vector<SharedWords> KeyFrameDatabase::KeyFramesSharingWords(const BowVector& query,
                                                                 std::vector<KeyFrameId> excluded) const {
  std::sort(excluded.begin(), excluded.end());
  std::unordered_map<KeyFrameId, int> common;
  {
    std::lock_guard lock(mutex_);
    for (const BowEntry& entry : query) {
      if (entry.word >= inverted_.size()) continue;
      for (KeyFrameId id : inverted_[entry.word]) ++common[id];
    }
  }
  std::vector<SharedWords> out;
  out.reserve(common.size());
  for (const auto& [id, count] : common) {
    if (!std::binary_search(excluded.begin(), excluded.end(), id)) out.push_back({id, count});
  }
  std::sort(out.begin(), out.end(), [](const SharedWords& a, const SharedWords& b) { return a.keyframe < b.keyframe; });
  return out;
}

std::vector<double> KeyFrameDatabase::Scores(const BowVector& query, const std::vector<KeyFrameId>& ids) const {
  std::vector<double> scores(ids.size(), 0.0);
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (auto it = vectors_.find(ids[i]); it != vectors_.end()) scores[i] = ScoreL1(query, it->second);
  }
  return scores;
}

}  // namespace dlslam::place

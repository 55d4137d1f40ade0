#pragma once
// The keyframes' bag-of-words, kept beside the map (the map itself knows no
// vocabulary): local mapping adds each new keyframe and erases culled ones;
// relocalization and loop closing query it. Thread-safe: the transform (the
// heavy part, ~1 ms) runs without any lock; the database and the direct
// index each take their own short lock.

#include <opencv2/core.hpp>

#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "dlslam/map/map_types.h"
#include "dlslam/place/keyframe_database.h"
#include "dlslam/place/vocabulary.h"

namespace dlslam::place {

// An image's bag of words and its direct index.
struct BowDescription {
  BowVector bow;
  FeatureVector features;
};

class KeyFrameIndex {
 public:
  // `direct_index_level`: tree level of the FeatureVector (2: 100 groups for
  // k = 10, as ORB-SLAM). Throws dlslam::Error for an empty vocabulary or a
  // level outside 1..levels.
  explicit KeyFrameIndex(std::shared_ptr<const Vocabulary> vocabulary, int direct_index_level = 2);

  // The description of ORB descriptors (CV_8UC1 rows of 32 bytes).
  BowDescription Describe(const cv::Mat& descriptors) const;
  // Describes and stores a keyframe (replacing an earlier entry).
  void Add(KeyFrameId keyframe, const cv::Mat& descriptors);
  // Forgets a keyframe; unknown ids are ignored.
  void Erase(KeyFrameId keyframe);

  const KeyFrameDatabase& database() const { return database_; }
  // The stored direct index of a keyframe; nullopt when not (or no longer) stored.
  std::optional<FeatureVector> Features(KeyFrameId keyframe) const;
  std::size_t size() const { return database_.size(); }

 private:
  std::shared_ptr<const Vocabulary> vocabulary_;
  int direct_index_level_;
  KeyFrameDatabase database_;
  mutable std::mutex mutex_;  // guards features_
  std::unordered_map<KeyFrameId, FeatureVector> features_;
};

}  // namespace dlslam::place

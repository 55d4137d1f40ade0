#include "dlslam/place/keyframe_index.h"

#include "dlslam/util/check.h"

namespace dlslam::place {

namespace {
std::size_t WordCount(const std::shared_ptr<const Vocabulary>& vocabulary) {
  DLSLAM_CHECK(vocabulary != nullptr && !vocabulary->empty(), "the keyframe index needs a vocabulary");
  return vocabulary->word_count();
}
}  // namespace

KeyFrameIndex::KeyFrameIndex(std::shared_ptr<const Vocabulary> vocabulary, int direct_index_level)
    : vocabulary_(std::move(vocabulary)), direct_index_level_(direct_index_level), database_(WordCount(vocabulary_)) {
  DLSLAM_CHECK(direct_index_level_ >= 1 && direct_index_level_ <= vocabulary_->levels(),
               "direct index level {} outside 1..{}", direct_index_level_, vocabulary_->levels());
}

BowDescription KeyFrameIndex::Describe(const cv::Mat& descriptors) const {
  BowDescription d;
  if (descriptors.empty()) return d;
  vocabulary_->Transform(DescriptorsFromMat(descriptors), direct_index_level_, d.bow, d.features);
  return d;
}

void KeyFrameIndex::Add(KeyFrameId keyframe, const cv::Mat& descriptors) {
  // Add and Erase of one keyframe come from the same (mapping) thread, so the
  // two stores cannot be left disagreeing by an Erase between them.
  BowDescription d = Describe(descriptors);  // outside every lock
  {
    std::lock_guard lock(mutex_);
    features_[keyframe] = std::move(d.features);
  }
  database_.Add(keyframe, std::move(d.bow));
}

void KeyFrameIndex::Erase(KeyFrameId keyframe) {
  database_.Erase(keyframe);
  std::lock_guard lock(mutex_);
  features_.erase(keyframe);
}

std::optional<FeatureVector> KeyFrameIndex::Features(KeyFrameId keyframe) const {
  std::lock_guard lock(mutex_);
  const auto it = features_.find(keyframe);
  if (it == features_.end()) return std::nullopt;
  return it->second;
}

}  // namespace dlslam::place

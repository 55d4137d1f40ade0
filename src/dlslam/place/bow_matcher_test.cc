#include "dlslam/place/bow_matcher.h"

#include <gtest/gtest.h>

#include <memory>

#include "dlslam/place/keyframe_index.h"
#include "dlslam/place/test_descriptors.h"
#include "dlslam/place/vocabulary_file.h"
#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

constexpr int kPoints = 300;
constexpr MapPointId kFirstPoint = 1000;

std::shared_ptr<const Vocabulary> Shipped() {
  static const auto vocabulary = std::make_shared<const Vocabulary>(LoadVocabulary(FindVocabulary()));
  return vocabulary;
}

Frame MakeFrame(const std::vector<Descriptor>& descriptors, const std::vector<float>& angles) {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat rows(static_cast<int>(descriptors.size()), 32, CV_8UC1);
  for (std::size_t i = 0; i < descriptors.size(); ++i) {
    const float x = static_cast<float>(10 + (i * 37) % 600), y = static_cast<float>(10 + (i * 53) % 460);
    keypoints.emplace_back(x, y, 31.f, angles[i], 1.f, 0);
    std::copy(descriptors[i].begin(), descriptors[i].end(), rows.ptr<std::uint8_t>(static_cast<int>(i)));
  }
  return Frame::Create(0.0, keypoints, rows, cv::Mat(), CameraPreset("freiburg3"), ScalePyramid{});
}

// A keyframe of random descriptors, each holding point kFirstPoint + k, and
// a frame that sees the same features in reversed order, each descriptor
// with 4 bits flipped: keypoint j of the frame is keypoint kPoints-1-j.
class BowMatcherTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(7);
    std::vector<Descriptor> kf_descriptors, frame_descriptors(kPoints);
    for (int k = 0; k < kPoints; ++k) kf_descriptors.push_back(testing::RandomDescriptor(rng));
    for (int k = 0; k < kPoints; ++k) frame_descriptors[kPoints - 1 - k] = testing::FlipBits(kf_descriptors[k], 4, rng);
    keyframe_ = std::make_unique<Frame>(MakeFrame(kf_descriptors, std::vector<float>(kPoints, 10.f)));
    frame_angles_.assign(kPoints, 40.f);  // every feature turned by 30 deg
    for (int k = 0; k < kPoints; ++k) points_.push_back(kFirstPoint + static_cast<MapPointId>(k));
    frame_descriptors_ = frame_descriptors;
  }
  std::vector<MapPointId> Match(const Frame& frame, const BowMatchOptions& options = {}) const {
    const KeyFrameIndex index(Shipped());
    return MatchByBow(frame, index.Describe(frame.descriptors()).features, *keyframe_,
                      index.Describe(keyframe_->descriptors()).features, points_, options);
  }
  std::unique_ptr<Frame> keyframe_;
  std::vector<Descriptor> frame_descriptors_;
  std::vector<float> frame_angles_;
  std::vector<MapPointId> points_;
};

TEST_F(BowMatcherTest, MatchesTheSameFeaturesAndNothingElse) {
  const Frame frame = MakeFrame(frame_descriptors_, frame_angles_);
  const std::vector<MapPointId> matches = Match(frame);
  int correct = 0;
  for (int j = 0; j < kPoints; ++j) {
    if (matches[j] == kNoId) continue;
    EXPECT_EQ(matches[j], kFirstPoint + static_cast<MapPointId>(kPoints - 1 - j)) << "keypoint " << j;
    ++correct;
  }
  // A flipped bit can move a random descriptor to another node (random
  // descriptors are far from every centre), which loses the match.
  EXPECT_GT(correct, kPoints / 2);
}

TEST_F(BowMatcherTest, LeavesOutPointlessFeaturesAndRotationOutliers) {
  // Every 20th turned by 210 deg: too few to be a dominant change.
  for (int j = 0; j < kPoints; j += 20) frame_angles_[j] = 220.f;
  Frame frame = MakeFrame(frame_descriptors_, frame_angles_);
  for (int k = 0; k < kPoints; k += 5) points_[k] = kNoId;  // keyframe features without a point
  const std::vector<MapPointId> matches = Match(frame);
  int matched = 0;
  for (int j = 0; j < kPoints; ++j) {
    if (matches[j] == kNoId) continue;
    ++matched;
    EXPECT_NE(j % 20, 0) << "rotation outlier " << j << " kept";
    EXPECT_NE((kPoints - 1 - j) % 5, 0) << "keyframe feature without a point matched at " << j;
  }
  EXPECT_GT(matched, kPoints / 4);
  // Without the rotation check the turned ones come back.
  BowMatchOptions no_rotation;
  no_rotation.check_rotation = false;
  const std::vector<MapPointId> all = Match(frame, no_rotation);
  int turned = 0;
  for (int j = 0; j < kPoints; j += 20) turned += all[j] != kNoId;
  EXPECT_GT(turned, 0);
}

TEST_F(BowMatcherTest, DistanceLimit) {
  const Frame frame = MakeFrame(frame_descriptors_, frame_angles_);
  BowMatchOptions strict;
  strict.max_distance = 3;  // below the 4 flipped bits
  const std::vector<MapPointId> matches = Match(frame, strict);
  for (MapPointId m : matches) EXPECT_EQ(m, kNoId);
  strict.max_distance = 300;
  EXPECT_THROW(strict.Check(), Error);
}

TEST(KeyFrameIndexTest, AddEraseAndFeatures) {
  cv::Mat rows(50, 32, CV_8UC1);
  cv::randu(rows, 0, 256);
  KeyFrameIndex index(Shipped());
  index.Add(4, rows);
  index.Add(9, rows);
  EXPECT_EQ(index.size(), 2u);
  const std::optional<FeatureVector> stored = index.Features(4);
  ASSERT_TRUE(stored.has_value());
  std::size_t features = 0;
  for (const FeatureNode& node : *stored) features += node.features.size();
  EXPECT_EQ(features, 50u);
  index.Erase(4);
  index.Erase(4);  // twice is harmless
  EXPECT_EQ(index.size(), 1u);
  EXPECT_FALSE(index.Features(4).has_value());
  EXPECT_FALSE(index.database().Contains(4));
  EXPECT_TRUE(index.database().Contains(9));
  EXPECT_THROW(KeyFrameIndex(Shipped(), 0), Error);
  EXPECT_THROW(KeyFrameIndex(nullptr), Error);
}

}  // namespace
}  // namespace dlslam::place

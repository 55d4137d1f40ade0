#include "dlslam/place/vocabulary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "dlslam/place/test_descriptors.h"
#include "dlslam/place/vocabulary_training.h"
#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

using testing::FlipBits;
using testing::MakeHierarchy;
using testing::RandomDescriptor;
using testing::SplitIntoImages;

TEST(Vocabulary, TrainingRecoversAKnownTwoLevelHierarchy) {
  std::mt19937 rng(11);
  const auto h = MakeHierarchy(3, 20, rng);
  const auto training = SplitIntoImages(h.members, 10);
  VocabularyOptions options;
  options.branching = 3;
  options.levels = 2;
  const Vocabulary vocabulary = TrainVocabulary(training, options);
  EXPECT_EQ(vocabulary.node_count(), 1u + 3u + 9u);
  ASSERT_EQ(vocabulary.word_count(), 9u);
  // One word per true leaf, and distinct leaves get distinct words.
  std::map<int, WordId> word_of_child;
  for (std::size_t m = 0; m < h.members.size(); ++m) {
    const WordId word = vocabulary.WordOf(h.members[m]);
    auto [it, inserted] = word_of_child.emplace(h.child_of_member[m], word);
    ASSERT_EQ(it->second, word) << "member " << m;
  }
  std::set<WordId> distinct;
  for (const auto& [child, word] : word_of_child) distinct.insert(word);
  EXPECT_EQ(distinct.size(), 9u);
  // Every word occurs in all 10 images (members are dealt round-robin): idf 0.
  for (WordWeight w : vocabulary.word_weights()) EXPECT_NEAR(w, 0.0f, 1e-6);
}

TEST(Vocabulary, IdfIsLogOfImagesOverImagesContainingTheWord) {
  std::mt19937 rng(12);
  // Three far-apart descriptor families: in 4 of 4 images, in 2 of 4, in 1 of 4.
  const Descriptor a = RandomDescriptor(rng), b = RandomDescriptor(rng), c = RandomDescriptor(rng);
  TrainingDescriptors training;
  for (int image = 0; image < 4; ++image) {
    std::vector<Descriptor> ds{FlipBits(a, 1, rng), FlipBits(a, 2, rng)};
    if (image < 2) ds.push_back(FlipBits(b, 1, rng));
    if (image == 3) ds.push_back(c);
    training.AddImage(ds);
  }
  VocabularyOptions options;
  options.branching = 3;
  options.levels = 1;
  const Vocabulary vocabulary = TrainVocabulary(training, options);
  ASSERT_EQ(vocabulary.word_count(), 3u);
  EXPECT_NEAR(vocabulary.word_weights()[vocabulary.WordOf(a)], 0.0, 1e-6);
  EXPECT_NEAR(vocabulary.word_weights()[vocabulary.WordOf(b)], std::log(2.0), 1e-6);
  EXPECT_NEAR(vocabulary.word_weights()[vocabulary.WordOf(c)], std::log(4.0), 1e-6);
}

TEST(Vocabulary, TransformGivesNormalisedTfIdfAndADirectIndexOverEveryFeature) {
  std::mt19937 rng(13);
  const auto h = MakeHierarchy(4, 10, rng);
  TrainingDescriptors training = SplitIntoImages(h.members, 5);
  training.AddImage(std::vector<Descriptor>{h.children[0]});  // makes idf differ between words
  VocabularyOptions options;
  options.branching = 4;
  options.levels = 3;
  const Vocabulary vocabulary = TrainVocabulary(training, options);

  std::vector<Descriptor> image(h.members.begin(), h.members.begin() + 37);
  BowVector bow;
  FeatureVector features;
  vocabulary.Transform(image, 1, bow, features);
  EXPECT_EQ(bow, vocabulary.Transform(image));
  double sum = 0.0;
  for (std::size_t i = 0; i < bow.size(); ++i) {
    sum += bow[i].weight;
    if (i > 0) {
      EXPECT_LT(bow[i - 1].word, bow[i].word);
    }
  }
  EXPECT_NEAR(sum, 1.0, 1e-5);
  // Weight of a word = occurrences x idf, normalised: check against counts.
  std::map<WordId, double> expected;
  double total = 0.0;
  for (const auto& d : image) {
    const WordId w = vocabulary.WordOf(d);
    expected[w] += vocabulary.word_weights()[w];
    total += vocabulary.word_weights()[w];
  }
  for (const auto& entry : bow) EXPECT_NEAR(entry.weight, expected[entry.word] / total, 1e-5);

  // Direct index at level 1: every feature exactly once, under the
  // level-1 ancestor its descent passes.
  std::vector<int> seen(image.size(), 0);
  for (std::size_t g = 0; g < features.size(); ++g) {
    if (g > 0) {
      EXPECT_LT(features[g - 1].node, features[g].node);
    }
    EXPECT_EQ(vocabulary.depth_of_node(features[g].node), 1);
    for (std::uint32_t f : features[g].features) {
      ++seen[f];
      NodeId node = 0;
      vocabulary.WordOf(image[f], 1, node);
      EXPECT_EQ(node, features[g].node);
    }
  }
  for (int count : seen) EXPECT_EQ(count, 1);
  EXPECT_THROW(vocabulary.Transform(image, 0, bow, features), Error);
  EXPECT_THROW(vocabulary.Transform(image, 4, bow, features), Error);
}

TEST(Vocabulary, TrainingIsDeterministicWhateverTheThreadCount) {
  std::mt19937 rng(14);
  std::vector<Descriptor> data;
  for (int i = 0; i < 3000; ++i) data.push_back(RandomDescriptor(rng));
  const auto training = SplitIntoImages(data, 30);
  VocabularyOptions options;
  options.branching = 5;
  options.levels = 3;
  options.seed = 77;
  options.threads = 1;
  const Vocabulary one = TrainVocabulary(training, options);
  options.threads = 3;
  const Vocabulary three = TrainVocabulary(training, options);
  EXPECT_EQ(one.centres(), three.centres());
  EXPECT_EQ(one.child_counts(), three.child_counts());
  EXPECT_EQ(one.word_weights(), three.word_weights());
  options.seed = 78;
  EXPECT_NE(TrainVocabulary(training, options).centres(), one.centres());
}

TEST(Vocabulary, DescentFollowsTheNearestChildAtEachLevel) {
  std::mt19937 rng(15);
  std::vector<Descriptor> data;
  for (int i = 0; i < 500; ++i) data.push_back(RandomDescriptor(rng));
  VocabularyOptions options;
  options.branching = 4;
  options.levels = 3;
  const Vocabulary vocabulary = TrainVocabulary(SplitIntoImages(data, 5), options);
  for (int trial = 0; trial < 50; ++trial) {
    const Descriptor d = RandomDescriptor(rng);
    NodeId node = 0;  // brute-force descent by the definition
    while (vocabulary.child_counts()[node] != 0) {
      NodeId best = vocabulary.first_child(node);
      for (NodeId c = best; c < vocabulary.first_child(node) + vocabulary.child_counts()[node]; ++c) {
        if (HammingDistance(vocabulary.centres()[c].data(), d.data()) <
            HammingDistance(vocabulary.centres()[best].data(), d.data())) {
          best = c;
        }
      }
      node = best;
    }
    EXPECT_EQ(vocabulary.WordOf(d), vocabulary.word_of_node(node));
  }
}

TEST(Vocabulary, ConstructorRejectsPartsThatAreNotATree) {
  const Descriptor zero{};
  // Root with 2 leaves: fine.
  EXPECT_NO_THROW(Vocabulary(2, 1, {zero, zero, zero}, {2, 0, 0}, {1.0f, 1.0f}));
  EXPECT_THROW(Vocabulary(2, 1, {zero, zero, zero}, {3, 0, 0}, {1.0f, 1.0f}), Error);     // > k children
  EXPECT_THROW(Vocabulary(2, 1, {zero, zero, zero}, {2, 0, 0}, {1.0f}), Error);           // weights
  EXPECT_THROW(Vocabulary(2, 1, {zero, zero, zero}, {1, 0, 0}, {1.0f, 1.0f}), Error);     // orphan
  EXPECT_THROW(Vocabulary(2, 1, {zero, zero, zero, zero}, {2, 1, 0, 0}, {1.0f, 1.0f}), Error);  // too deep
  EXPECT_THROW(Vocabulary(2, 1, {zero, zero}, {2, 0, 0}, {1.0f, 1.0f}), Error);           // centres
  EXPECT_TRUE(Vocabulary().Transform(std::vector<Descriptor>{zero}).empty());
}

TEST(Vocabulary, DescriptorsFromMatCopiesRows) {
  cv::Mat rows(3, 32, CV_8UC1);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 32; ++c) rows.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(r * 32 + c);
  }
  const auto ds = DescriptorsFromMat(rows);
  ASSERT_EQ(ds.size(), 3u);
  EXPECT_EQ(ds[2][5], 2 * 32 + 5);
  EXPECT_THROW(DescriptorsFromMat(cv::Mat(2, 31, CV_8UC1)), Error);
  EXPECT_TRUE(DescriptorsFromMat(cv::Mat()).empty());
}

}  // namespace
}  // namespace dlslam::place

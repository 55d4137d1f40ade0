#include "dlslam/place/keyframe_database.h"

#include <gtest/gtest.h>

#include <random>

#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

BowVector RandomVector(std::mt19937& rng, int words, int vocabulary) {
  std::uniform_int_distribution<int> word(0, vocabulary - 1);
  BowVector v;
  for (int i = 0; i < words; ++i) v.push_back({static_cast<WordId>(word(rng)), 1.0f});
  SortAndMerge(v);
  NormalizeL1(v);
  return v;
}

TEST(KeyFrameDatabase, SharingWordsMatchesBruteForceAfterAddsReplacementsAndErases) {
  std::mt19937 rng(31);
  constexpr int kWords = 200;
  KeyFrameDatabase database(kWords);
  std::map<KeyFrameId, BowVector> truth;
  for (KeyFrameId id = 0; id < 60; ++id) {
    truth[id] = RandomVector(rng, 20, kWords);
    database.Add(id, truth[id]);
  }
  for (KeyFrameId id = 0; id < 60; id += 7) database.Erase(id), truth.erase(id);
  for (KeyFrameId id = 1; id < 60; id += 11) {  // replace
    truth[id] = RandomVector(rng, 20, kWords);
    database.Add(id, truth[id]);
  }
  database.Erase(1000);  // unknown: ignored
  EXPECT_EQ(database.size(), truth.size());

  const BowVector query = RandomVector(rng, 30, kWords);
  const std::vector<KeyFrameId> excluded{5, 3};
  const auto sharing = database.KeyFramesSharingWords(query, excluded);
  std::vector<SharedWords> expected;
  for (const auto& [id, bow] : truth) {
    const int common = CommonWords(query, bow);
    if (common > 0 && id != 3 && id != 5) expected.push_back({id, common});
  }
  ASSERT_EQ(sharing.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(sharing[i].keyframe, expected[i].keyframe);
    EXPECT_EQ(sharing[i].common_words, expected[i].common_words);
  }
  std::vector<KeyFrameId> ids{2, 0, 999};
  const auto scores = database.Scores(query, ids);
  EXPECT_DOUBLE_EQ(scores[0], ScoreL1(query, truth[2]));
  EXPECT_EQ(scores[1], 0.0);  // erased
  EXPECT_EQ(scores[2], 0.0);  // never added
  EXPECT_EQ(database.Find(2), truth[2]);
  EXPECT_FALSE(database.Find(0).has_value());
  database.Clear();
  EXPECT_EQ(database.size(), 0u);
  EXPECT_TRUE(database.KeyFramesSharingWords(query).empty());
}

TEST(KeyFrameDatabase, RejectsWordsOutsideTheVocabularyAndUnsortedVectors) {
  KeyFrameDatabase database(10);
  EXPECT_THROW(database.Add(1, {{10, 1.0f}}), Error);
  EXPECT_THROW(database.Add(1, {{3, 0.5f}, {2, 0.5f}}), Error);
  EXPECT_THROW(database.Add(1, {{3, 0.5f}, {3, 0.5f}}), Error);
  EXPECT_EQ(database.size(), 0u);
}

}  // namespace
}  // namespace dlslam::place

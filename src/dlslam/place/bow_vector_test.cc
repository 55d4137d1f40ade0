#include "dlslam/place/bow_vector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace dlslam::place {
namespace {

BowVector RandomVector(std::mt19937& rng, int words, int vocabulary) {
  std::uniform_int_distribution<int> word(0, vocabulary - 1);
  std::uniform_real_distribution<float> weight(0.01f, 1.0f);
  BowVector v;
  for (int i = 0; i < words; ++i) v.push_back({static_cast<WordId>(word(rng)), weight(rng)});
  SortAndMerge(v);
  NormalizeL1(v);
  return v;
}

// 1 - 0.5 |a - b|_1 over dense vectors: the definition, not the merge.
double DenseScore(const BowVector& a, const BowVector& b) {
  std::map<WordId, double> difference;
  for (const auto& e : a) difference[e.word] += e.weight;
  for (const auto& e : b) difference[e.word] -= e.weight;
  double l1 = 0.0;
  for (const auto& [word, value] : difference) l1 += std::abs(value);
  return 1.0 - 0.5 * l1;
}

TEST(BowVector, SortAndMergeAddsRepeatedWords) {
  BowVector v{{7, 1.0f}, {2, 0.5f}, {7, 2.0f}, {3, 1.0f}, {2, 0.25f}};
  SortAndMerge(v);
  const BowVector expected{{2, 0.75f}, {3, 1.0f}, {7, 3.0f}};
  EXPECT_EQ(v, expected);
}

TEST(BowVector, NormalizeL1MakesWeightsSumToOne) {
  BowVector v{{1, 2.0f}, {4, 6.0f}};
  NormalizeL1(v);
  EXPECT_FLOAT_EQ(v[0].weight, 0.25f);
  EXPECT_FLOAT_EQ(v[1].weight, 0.75f);
  BowVector zeros{{1, 0.0f}};
  NormalizeL1(zeros);
  EXPECT_EQ(zeros[0].weight, 0.0f);
}

TEST(BowVector, ScoreIsOneForIdenticalZeroForDisjoint) {
  std::mt19937 rng(1);
  const BowVector a = RandomVector(rng, 50, 1000);
  EXPECT_NEAR(ScoreL1(a, a), 1.0, 1e-6);
  BowVector shifted = a;
  for (auto& e : shifted) e.word += 1000;  // no word in common
  EXPECT_EQ(ScoreL1(a, shifted), 0.0);
  EXPECT_EQ(ScoreL1(a, {}), 0.0);
}

TEST(BowVector, ScoreMatchesTheL1DefinitionAndIsSymmetric) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 200; ++trial) {
    const BowVector a = RandomVector(rng, 1 + trial % 40, 60);
    const BowVector b = RandomVector(rng, 1 + trial % 23, 60);
    ASSERT_NEAR(ScoreL1(a, b), DenseScore(a, b), 1e-6);
    ASSERT_DOUBLE_EQ(ScoreL1(a, b), ScoreL1(b, a));
  }
}

TEST(BowVector, CommonWordsCountsSharedWords) {
  const BowVector a{{1, 0.5f}, {3, 0.25f}, {9, 0.25f}};
  const BowVector b{{0, 0.5f}, {3, 0.25f}, {9, 0.25f}, {10, 0.0f}};
  EXPECT_EQ(CommonWords(a, b), 2);
  EXPECT_EQ(CommonWords(a, {}), 0);
}

}  // namespace
}  // namespace dlslam::place

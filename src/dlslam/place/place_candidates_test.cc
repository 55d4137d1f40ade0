#include "dlslam/place/place_candidates.h"

#include <gtest/gtest.h>

#include <map>

#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

// A vector of `words` equal weights over words [first, first + words).
BowVector Block(WordId first, int words) {
  BowVector v;
  for (int i = 0; i < words; ++i) v.push_back({first + static_cast<WordId>(i), 1.0f});
  NormalizeL1(v);
  return v;
}

class Covisibility {
 public:
  void Connect(KeyFrameId a, KeyFrameId b) {
    graph_[a].push_back(b);
    graph_[b].push_back(a);
  }
  CovisibleNeighbours Function() const {
    return [this](KeyFrameId id, int count) {
      auto it = graph_.find(id);
      std::vector<KeyFrameId> out = it == graph_.end() ? std::vector<KeyFrameId>{} : it->second;
      if (static_cast<int>(out.size()) > count) out.resize(static_cast<std::size_t>(count));
      return out;
    };
  }

 private:
  std::map<KeyFrameId, std::vector<KeyFrameId>> graph_;
};

// Query = words 0..99. Keyframes: a group {10, 11, 12} that saw the place
// (90, 85, 80 shared words), a lone look-alike 20 (92 shared words), a
// weak match 30 (30 shared), and the query's own neighbours 1, 2.
class CandidatesTest : public ::testing::Test {
 protected:
  CandidatesTest() : database_(1000) {
    query_ = Block(0, 100);
    database_.Add(1, Block(5, 100));  // connected: 95 shared
    database_.Add(2, Block(50, 100));  // connected: 50 shared
    database_.Add(10, Block(10, 100));
    database_.Add(11, Block(15, 100));
    database_.Add(12, Block(20, 100));
    database_.Add(20, Block(8, 100));
    database_.Add(30, Block(70, 100));
    database_.Add(40, Block(500, 100));  // shares nothing
    covisibility_.Connect(99, 1);
    covisibility_.Connect(99, 2);
    covisibility_.Connect(10, 11);
    covisibility_.Connect(10, 12);
    covisibility_.Connect(11, 12);
  }
  KeyFrameDatabase database_;
  BowVector query_;
  Covisibility covisibility_;
};

TEST_F(CandidatesTest, MinScoreIsTheLowestScoreAgainstTheNeighbours) {
  EXPECT_NEAR(MinScore(database_, query_, {1, 2}), 0.5, 1e-6);
  EXPECT_EQ(MinScore(database_, query_, {}), 1.0);
  EXPECT_NEAR(MinScore(database_, query_, {1, 777}), 0.95, 1e-6);
}

TEST_F(CandidatesTest, LoopCandidatesPreferAGroupOverALoneLookAlike) {
  const double min_score = MinScore(database_, query_, {1, 2});  // 0.5
  const auto candidates =
      DetectLoopCandidates(database_, 99, query_, {1, 2}, min_score, covisibility_.Function());
  // Shared words: 20 -> 92, 10 -> 90, 11 -> 85, 12 -> 80, 30 -> 30: the
  // common-word cut at 0.8 * 92 = 73.6 drops 30. Groups: 10 + 11 + 12 =
  // 2.55 (best 10), 20 alone 0.92 < 0.75 * 2.55: only the group's best remains.
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_EQ(candidates[0].keyframe, 10u);
  EXPECT_NEAR(candidates[0].score, 0.90, 1e-6);
  EXPECT_NEAR(candidates[0].group_score, 0.90 + 0.85 + 0.80, 1e-5);
}

TEST_F(CandidatesTest, LoopCandidatesNeverIncludeConnectedKeyFramesOrTheQuery) {
  database_.Add(99, query_);
  const auto candidates = DetectLoopCandidates(database_, 99, query_, {1, 2}, 0.0, covisibility_.Function());
  for (const auto& c : candidates) {
    EXPECT_NE(c.keyframe, 99u);
    EXPECT_NE(c.keyframe, 1u);
    EXPECT_NE(c.keyframe, 2u);
  }
}

TEST_F(CandidatesTest, MinScoreAndRetainRatioFilter) {
  // Nothing reaches a score of 0.95.
  EXPECT_TRUE(DetectLoopCandidates(database_, 99, query_, {1, 2}, 0.95, covisibility_.Function()).empty());
  // Retaining every group keeps the look-alike too.
  CandidateOptions options;
  options.retain_ratio = 0.0;
  const auto all = DetectLoopCandidates(database_, 99, query_, {1, 2}, 0.5, covisibility_.Function(), options);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].keyframe, 10u);
  EXPECT_EQ(all[1].keyframe, 20u);
  // No grouping: the best single keyframe wins.
  options.group_size = 0;
  options.retain_ratio = 0.75;
  const auto single = DetectLoopCandidates(database_, 99, query_, {1, 2}, 0.5, covisibility_.Function(), options);
  ASSERT_FALSE(single.empty());
  EXPECT_EQ(single[0].keyframe, 20u);
}

TEST_F(CandidatesTest, RelocalizationConsidersEveryKeyFrame) {
  // Keyframe 1 (95 shared words), excluded from loops as the query's
  // neighbour, is now scored; alone (its neighbour 99 is not stored) it
  // accumulates 0.95, below 0.75 x 2.55 of the group 10 + 11 + 12.
  const auto candidates = DetectRelocalizationCandidates(database_, query_, covisibility_.Function());
  ASSERT_FALSE(candidates.empty());
  EXPECT_EQ(candidates[0].keyframe, 10u);  // group 10+11+12 still accumulates most
  bool has_one = false;
  for (const auto& c : candidates) has_one |= c.keyframe == 1u;
  EXPECT_FALSE(has_one);  // 0.95 < 0.75 * 2.55
  CandidateOptions options;
  options.group_size = 0;
  const auto single = DetectRelocalizationCandidates(database_, query_, covisibility_.Function(), options);
  ASSERT_FALSE(single.empty());
  EXPECT_EQ(single[0].keyframe, 1u);
}

TEST_F(CandidatesTest, EmptyDatabaseAndBadOptions) {
  KeyFrameDatabase empty(1000);
  EXPECT_TRUE(DetectRelocalizationCandidates(empty, query_, covisibility_.Function()).empty());
  CandidateOptions bad;
  bad.retain_ratio = 1.5;
  EXPECT_THROW(DetectRelocalizationCandidates(database_, query_, covisibility_.Function(), bad), Error);
}

}  // namespace
}  // namespace dlslam::place

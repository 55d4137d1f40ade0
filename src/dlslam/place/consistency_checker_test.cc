#include "dlslam/place/consistency_checker.h"

#include <gtest/gtest.h>

#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

using Ids = std::vector<KeyFrameId>;

TEST(ConsistencyChecker, AcceptsACandidateSeenAtFourSuccessiveQueries) {
  ConsistencyChecker checker(3);
  // The same place seen from neighbouring keyframes: groups overlap.
  EXPECT_TRUE(checker.Update({{10, {11, 12}}}).empty());  // consistency 0
  EXPECT_TRUE(checker.Update({{11, {10, 13}}}).empty());  // 1
  EXPECT_TRUE(checker.Update({{13, {11, 14}}}).empty());  // 2
  EXPECT_EQ(checker.Update({{14, {13, 15}}}), Ids{14});   // 3: accepted
  ASSERT_EQ(checker.groups().size(), 1u);
  EXPECT_EQ(checker.groups()[0].consistency, 3);
  EXPECT_EQ(checker.groups()[0].keyframes, (Ids{13, 14, 15}));
}

TEST(ConsistencyChecker, AGapOrADifferentPlaceRestartsTheCount) {
  ConsistencyChecker checker(3);
  checker.Update({{10, {11}}});
  checker.Update({{11, {10}}});
  checker.Update({});  // no candidate at this keyframe: history cleared
  EXPECT_TRUE(checker.groups().empty());
  checker.Update({{10, {11}}});
  checker.Update({{50, {51}}});  // elsewhere: starts at 0
  ASSERT_EQ(checker.groups().size(), 1u);
  EXPECT_EQ(checker.groups()[0].consistency, 0);
  EXPECT_TRUE(checker.Update({{10, {11}}}).empty());
}

TEST(ConsistencyChecker, OnePreviousGroupIsContinuedOnce) {
  ConsistencyChecker checker(1);
  checker.Update({{10, {11, 12}}});
  // Both new candidates overlap the one previous group: both are consistent
  // with it (both accepted), but only the first continues it.
  EXPECT_EQ(checker.Update({{11, {}}, {12, {}}}), (Ids{11, 12}));
  ASSERT_EQ(checker.groups().size(), 1u);
  EXPECT_EQ(checker.groups()[0].keyframes, Ids{11});
}

TEST(ConsistencyChecker, CandidatesOnlyOverlappingEachOtherStayApart) {
  ConsistencyChecker checker(2);
  checker.Update({{1, {2}}, {7, {8}}});
  checker.Update({{2, {}}, {8, {}}});
  EXPECT_EQ(checker.Update({{2, {1}}, {9, {8}}}), (Ids{2, 9}));
  EXPECT_THROW(ConsistencyChecker(0), Error);
  checker.Reset();
  EXPECT_TRUE(checker.groups().empty());
}

}  // namespace
}  // namespace dlslam::place

#include "dlslam/place/revisit_evaluation.h"

#include <gtest/gtest.h>

#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

RevisitFrame Frame(int index, double x, WordId word) {
  return {index, SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(x, 0, 0)), {{word, 1.0f}}};
}

TEST(EvaluateRevisits, CountsQueriesCorrectMatchesAndChance) {
  // Frames 0 and 200 are at the same place with the same word: a found
  // revisit. Frame 100 is 2 m away; 300 revisits 100's place but looks like
  // frame 0 (word 1), so its best match (0 or 200, score 1) is wrong.
  const std::vector<RevisitFrame> frames{Frame(0, 0.0, 1), Frame(100, 2.0, 2), Frame(200, 0.1, 1),
                                         Frame(300, 2.0, 1)};
  const RevisitEvaluation result = EvaluateRevisits(frames);
  // Queries: 0 (revisit 200), 100 (300), 200 (0), 300 (100).
  EXPECT_EQ(result.queries, 4);
  // 0 -> 200 right; 100 scores 0 with everyone: the first far frame (0) is
  // wrong; 200 -> 0 right; 300 -> 0 wrong.
  EXPECT_EQ(result.correct, 2);
  EXPECT_DOUBLE_EQ(result.precision_at_1, 0.5);
  // Every other frame is >= 100 frames away; each query has exactly one
  // acceptable frame among its three far ones.
  EXPECT_DOUBLE_EQ(result.chance, 1.0 / 3.0);
}

TEST(EvaluateRevisits, RejectsAnAcceptanceTighterThanTheRevisitTolerance) {
  EXPECT_THROW(EvaluateRevisits({}, {100, 0.5, 20.0, 0.3, 30.0}), Error);
  EXPECT_EQ(EvaluateRevisits({}).queries, 0);
}

}  // namespace
}  // namespace dlslam::place

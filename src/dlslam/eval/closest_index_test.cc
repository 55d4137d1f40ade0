#include "dlslam/eval/closest_index.h"

#include <gtest/gtest.h>

#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

const std::vector<double> kZeroToNine = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};

TEST(FindClosestIndexTest, ExactHitReturnsItsIndex) {
  for (std::size_t k = 0; k < kZeroToNine.size(); ++k) {
    EXPECT_EQ(FindClosestIndex(kZeroToNine, static_cast<double>(k)), k);
  }
}

TEST(FindClosestIndexTest, ReturnsNearestWhenUnambiguous) {
  EXPECT_EQ(FindClosestIndex(kZeroToNine, 3.2), 3u);
  EXPECT_EQ(FindClosestIndex(kZeroToNine, 3.8), 4u);
  EXPECT_EQ(FindClosestIndex(kZeroToNine, 8.9), 9u);
}

TEST(FindClosestIndexTest, OutsideTheRangeClampsToTheEnds) {
  EXPECT_EQ(FindClosestIndex(kZeroToNine, -5.0), 0u);
  EXPECT_EQ(FindClosestIndex(kZeroToNine, 100.0), 9u);
  EXPECT_EQ(FindClosestIndex(std::vector<double>{4.0}, 100.0), 0u);
}

// Ties go to whichever neighbour the search probes first, so the lower one
// wins for 2.5 and the upper one for 6.5 (traced by hand through the TUM
// search: 2.5 probes 5, 2, 4, 3; 6.5 probes 5, 8, 7, 6).
TEST(FindClosestIndexTest, TieGoesToTheFirstProbedNeighbour) {
  EXPECT_EQ(FindClosestIndex(kZeroToNine, 2.5), 2u);
  EXPECT_EQ(FindClosestIndex(kZeroToNine, 6.5), 7u);
  // Before any probe, element 0 is the best; a tie with it keeps 0.
  EXPECT_EQ(FindClosestIndex(std::vector<double>{0, 1}, 0.5), 0u);
}

TEST(FindClosestIndexTest, EmptyListThrows) {
  EXPECT_THROW(FindClosestIndex(std::vector<double>{}, 1.0), Error);
}

}  // namespace
}  // namespace dlslam::eval

#include "dlslam/eval/stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

TEST(ErrorStatsTest, OddCount) {
  const std::vector<double> e = {3, 1, 2};
  const ErrorStats s = ComputeErrorStats(e);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(14.0 / 3.0));
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
  EXPECT_DOUBLE_EQ(s.median, 2.0);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(2.0 / 3.0));  // population: divides by n
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 3.0);
}

TEST(ErrorStatsTest, EvenCountMedianAveragesTheMiddleTwo) {
  const std::vector<double> e = {4, 1, 3, 2};
  const ErrorStats s = ComputeErrorStats(e);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4.0));
}

TEST(ErrorStatsTest, SingleValue) {
  const ErrorStats s = ComputeErrorStats(std::vector<double>{0.7});
  EXPECT_DOUBLE_EQ(s.rmse, 0.7);
  EXPECT_DOUBLE_EQ(s.median, 0.7);
  EXPECT_DOUBLE_EQ(s.std, 0.0);
}

TEST(ErrorStatsTest, SmallSpreadOnLargeValuesKeepsItsStd) {
  // sum_sq / n - mean^2 would lose these digits entirely.
  const std::vector<double> e = {1e8 + 1, 1e8 - 1};
  EXPECT_DOUBLE_EQ(ComputeErrorStats(e).std, 1.0);
}

TEST(ErrorStatsTest, HugeErrorsDoNotOverflow) {
  const std::vector<double> e = {3e200, 4e200, 3e200, 4e200};
  const ErrorStats s = ComputeErrorStats(e);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(12.5) * 1e200);
  EXPECT_DOUBLE_EQ(s.mean, 3.5e200);
  EXPECT_DOUBLE_EQ(s.std, 0.5e200);
  EXPECT_DOUBLE_EQ(s.median, 3.5e200);
  const std::vector<double> zeros = {0.0, 0.0};
  EXPECT_EQ(ComputeErrorStats(zeros).rmse, 0.0);
}

TEST(ErrorStatsTest, EmptyThrows) {
  EXPECT_THROW(ComputeErrorStats(std::vector<double>{}), Error);
  EXPECT_THROW(Median(std::vector<double>{}), Error);
}

}  // namespace
}  // namespace dlslam::eval

#include "dlslam/eval/associate.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

using Matches = std::vector<TimestampMatch>;

// The rule spelled out over all n * m pairs, as an oracle for the windowed search.
Matches BruteForce(const std::vector<double>& gt, const std::vector<double>& est, double offset,
                   double max_diff) {
  std::vector<std::tuple<double, double, double, std::size_t, std::size_t>> c;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    for (std::size_t j = 0; j < est.size(); ++j) {
      const double d = std::abs(gt[i] - (est[j] + offset));
      if (d < max_diff) c.emplace_back(d, gt[i], est[j], i, j);
    }
  }
  std::sort(c.begin(), c.end());
  std::set<std::size_t> used_gt;
  std::set<std::size_t> used_est;
  Matches out;
  for (const auto& [d, a, b, i, j] : c) {
    if (used_gt.count(i) || used_est.count(j)) continue;
    used_gt.insert(i);
    used_est.insert(j);
    out.push_back({i, j});
  }
  std::sort(out.begin(), out.end(), [](auto& x, auto& y) { return x.gt_index < y.gt_index; });
  return out;
}

Matches Match(const std::vector<double>& gt, const std::vector<double>& est, double max_diff,
            double offset = 0.0) {
  return AssociateTimestamps(gt, est, {max_diff, offset});
}

TEST(AssociateTest, SmallestDifferenceFirstEvenIfPairsCross) {
  // (gt1, est0) is closest and taken first; gt0 then gets est1 (0.019 < 0.02).
  const Matches m = Match({1.000, 1.012}, {1.007, 1.019}, 0.02);
  EXPECT_EQ(m, (Matches{{0, 1}, {1, 0}}));
}

TEST(AssociateTest, EachStampUsedOnce) {
  const Matches m = Match({1.0, 1.01, 1.02, 1.03}, {1.012}, 0.05);
  EXPECT_EQ(m, (Matches{{1, 0}}));
  const Matches m2 = Match({1.012}, {1.0, 1.01, 1.02, 1.03}, 0.05);
  EXPECT_EQ(m2, (Matches{{0, 1}}));
}

TEST(AssociateTest, MaxDiffIsStrict) {
  // 0.5 apart exactly (binary-exact numbers).
  EXPECT_TRUE(Match({1.0}, {1.5}, 0.5).empty());
  EXPECT_EQ(Match({1.0}, {1.5}, 0.5000001).size(), 1u);
}

TEST(AssociateTest, TiesGoToTheSmallerGtThenTheSmallerEstStamp) {
  EXPECT_EQ(Match({1.0, 2.0}, {1.5}, 0.6), (Matches{{0, 0}}));
  EXPECT_EQ(Match({1.5}, {1.0, 2.0}, 0.6), (Matches{{0, 0}}));
}

TEST(AssociateTest, OffsetShiftsTheEstimate) {
  EXPECT_TRUE(Match({10.0, 11.0}, {5.0, 6.0}, 0.02).empty());
  EXPECT_EQ(Match({10.0, 11.0}, {5.0, 6.0}, 0.02, 5.0), (Matches{{0, 0}, {1, 1}}));
}

TEST(AssociateTest, AgreesWithAllPairsOnRandomStreams) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> gt;
    std::vector<double> est;
    double t = 1305031102.0 + trial;
    for (int k = 0; k < 300; ++k) gt.push_back(t += 0.01 + jitter(rng) / 4);
    t = 1305031102.0 + trial;
    for (int k = 0; k < 120; ++k) est.push_back(t += 0.025 + jitter(rng));
    const double offset = trial % 3 == 0 ? 0.0 : 0.013 * trial;
    const double max_diff = trial % 2 == 0 ? 0.02 : 0.007;
    EXPECT_EQ(Match(gt, est, max_diff, offset), BruteForce(gt, est, offset, max_diff)) << trial;
  }
}

TEST(AssociateTest, BadInputThrows) {
  EXPECT_THROW(Match({1.0, 1.0}, {1.0}, 0.02), Error);  // not increasing
  EXPECT_THROW(Match({1.0}, {2.0, 1.0}, 0.02), Error);
  EXPECT_THROW(Match({1.0}, {1.0}, 0.0), Error);
  EXPECT_THROW(Match({1.0}, {1.0}, -1.0), Error);
}

}  // namespace
}  // namespace dlslam::eval

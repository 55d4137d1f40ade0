#include "dlslam/io/association.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>

#include "dlslam/io/image_list.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

// The rule as associate.py states it, quadratic and literal: every pair,
// sorted by (diff, a, b), taken greedily, then sorted by (a, b).
std::vector<IndexPair> BruteForce(const std::vector<double>& a, const std::vector<double>& b,
                                  double offset, double max_diff) {
  std::vector<std::tuple<double, double, double, std::size_t, std::size_t>> all;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double diff = std::abs(a[i] - (b[j] + offset));
      if (diff < max_diff) all.emplace_back(diff, a[i], b[j], i, j);
    }
  }
  std::sort(all.begin(), all.end());
  std::vector<bool> used_a(a.size()), used_b(b.size());
  std::vector<std::tuple<double, double, std::size_t, std::size_t>> taken;
  for (const auto& [diff, ta, tb, i, j] : all) {
    if (used_a[i] || used_b[j]) continue;
    used_a[i] = used_b[j] = true;
    taken.emplace_back(ta, tb, i, j);
  }
  std::sort(taken.begin(), taken.end());
  std::vector<IndexPair> pairs;
  for (const auto& t : taken) pairs.push_back({std::get<2>(t), std::get<3>(t)});
  return pairs;
}

TEST(AssociateTimestamps, NearestWinsAndEachTimestampIsUsedOnce) {
  // 0.104 is nearest to both 0.1 and 0.11; 0.1 is nearer (0.004 < 0.006) and
  // takes it, 0.11 falls back to 0.118 (0.008).
  const std::vector<double> rgb = {0.1, 0.11, 0.5};
  const std::vector<double> depth = {0.104, 0.118, 0.9};
  const auto pairs = AssociateTimestamps(rgb, depth);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0], (IndexPair{0, 0}));
  EXPECT_EQ(pairs[1], (IndexPair{1, 1}));
}

TEST(AssociateTimestamps, EqualDifferencesGoToTheEarlierTimestamp) {
  const auto pairs = AssociateTimestamps({0.0, 0.5}, {0.25}, 0.0, 0.3);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], (IndexPair{0, 0}));
}

TEST(AssociateTimestamps, MaxDiffIsStrictAndOffsetShiftsTheSecondList) {
  EXPECT_TRUE(AssociateTimestamps({0.0}, {0.25}, 0.0, 0.25).empty());
  EXPECT_EQ(AssociateTimestamps({0.0}, {0.25}, 0.0, 0.2500001).size(), 1u);
  EXPECT_EQ(AssociateTimestamps({10.0}, {0.0}, 10.0, 0.01).size(), 1u);
  EXPECT_TRUE(AssociateTimestamps({10.0}, {0.0}, 0.0, 0.01).empty());
}

TEST(AssociateTimestamps, ResultIsSortedByTimeForUnsortedInput) {
  const auto pairs = AssociateTimestamps({3.0, 1.0, 2.0}, {2.001, 0.999, 3.002});
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0], (IndexPair{1, 1}));
  EXPECT_EQ(pairs[1], (IndexPair{2, 0}));
  EXPECT_EQ(pairs[2], (IndexPair{0, 2}));
}

TEST(AssociateTimestamps, MatchesTheQuadraticRuleOnRandomLists) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    // Coarse grids make ties and near-boundary differences common.
    const double step = (trial % 3 == 0) ? 0.005 : 0.0001;
    std::uniform_int_distribution<int> count(0, 60), tick(0, static_cast<int>(2.0 / step));
    const double base = (trial % 2 == 0) ? 0.0 : 1341846313.0;
    std::vector<double> a(static_cast<std::size_t>(count(rng))),
        b(static_cast<std::size_t>(count(rng)));
    for (double& t : a) t = base + tick(rng) * step;
    for (double& t : b) t = base + tick(rng) * step;
    const double offset = (trial % 5 == 0) ? 0.01 : 0.0;
    const double max_diff = (trial % 4 == 0) ? 0.02 : 0.035;
    ASSERT_EQ(AssociateTimestamps(a, b, offset, max_diff), BruteForce(a, b, offset, max_diff))
        << "trial " << trial;
  }
}

TEST(AssociateTimestamps, RejectsNonFiniteInput) {
  EXPECT_THROW(AssociateTimestamps({std::nan("")}, {0.0}), Error);
  EXPECT_THROW(AssociateTimestamps({0.0}, {0.0}, 0.0, 0.0), Error);
  EXPECT_THROW(AssociateTimestamps({0.0}, {0.0}, std::numeric_limits<double>::infinity()), Error);
}

// The published TUM association files list pairs that associate.py chose from
// the full lists; associating their own RGB and depth stamps again must give
// back exactly those pairs.
TEST(AssociateTimestamps, ReproducesTumAssociationFiles) {
  DLSLAM_REQUIRE_SHARED_DATA(dir, "tum/associations");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const auto pairs = ReadAssociationFile(entry.path());
    std::vector<double> rgb, depth;
    for (const auto& p : pairs) {
      rgb.push_back(p.rgb.timestamp);
      depth.push_back(p.depth.timestamp);
    }
    const auto associated = AssociateTimestamps(rgb, depth);
    ASSERT_EQ(associated.size(), pairs.size()) << entry.path();
    for (std::size_t k = 0; k < associated.size(); ++k) {
      ASSERT_EQ(associated[k], (IndexPair{k, k})) << entry.path() << " pair " << k;
    }
    ++files;
  }
  EXPECT_GE(files, 10);
}

}  // namespace
}  // namespace dlslam::io

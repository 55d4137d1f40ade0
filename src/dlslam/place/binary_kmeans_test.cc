#include "dlslam/place/binary_kmeans.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>

#include "dlslam/place/test_descriptors.h"
#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

using testing::FlipBits;
using testing::RandomDescriptor;

std::vector<std::uint32_t> AllIndices(std::size_t n) {
  std::vector<std::uint32_t> indices(n);
  std::iota(indices.begin(), indices.end(), 0u);
  return indices;
}

TEST(MajorityDescriptor, MatchesBitByBitVote) {
  std::mt19937 rng(3);
  for (int n : {1, 2, 3, 7, 254, 255, 256, 600}) {
    std::vector<Descriptor> ds;
    for (int i = 0; i < n; ++i) ds.push_back(RandomDescriptor(rng));
    Descriptor expected{};
    for (int bit = 0; bit < 256; ++bit) {
      int ones = 0;
      for (const auto& d : ds) ones += (d[bit / 8] >> (bit % 8)) & 1;
      if (2 * ones > n) expected[bit / 8] = static_cast<std::uint8_t>(expected[bit / 8] | (1 << (bit % 8)));
    }
    ASSERT_EQ(MajorityDescriptor(ds), expected) << n << " descriptors";
  }
}

TEST(NearestCentre, TakesTheClosestAndTheFirstOfEquals) {
  Descriptor zero{}, one{}, two{};
  one[0] = 1;
  two[0] = 3;
  const std::vector<Descriptor> centres{two, one, one};
  EXPECT_EQ(NearestCentre(centres, zero), 1u);
  EXPECT_EQ(NearestCentre(centres, two), 0u);
}

TEST(ClusterBinary, SeedingFindsEveryDistinctValueWhenThereAreExactlyK) {
  // k distinct values, many copies: k-means++ never re-picks a chosen value
  // (its distance is 0), so any seed must give exactly these centres.
  std::mt19937 rng(4);
  std::vector<Descriptor> distinct;
  for (int i = 0; i < 5; ++i) distinct.push_back(RandomDescriptor(rng));
  std::vector<Descriptor> data;
  for (int copy = 0; copy < 40; ++copy) data.insert(data.end(), distinct.begin(), distinct.end());
  const auto members = AllIndices(data.size());
  for (std::uint64_t seed = 0; seed < 10; ++seed) {
    const auto result = ClusterBinary(data, members, {5, 10}, seed);
    ASSERT_EQ(result.centres.size(), 5u);
    std::set<Descriptor> found(result.centres.begin(), result.centres.end());
    EXPECT_EQ(found, std::set<Descriptor>(distinct.begin(), distinct.end()));
    for (std::size_t i = 0; i < data.size(); ++i) ASSERT_EQ(result.centres[result.assignment[i]], data[i]);
  }
}

TEST(ClusterBinary, FewerDistinctValuesThanKGiveFewerCentres) {
  std::mt19937 rng(5);
  const Descriptor a = RandomDescriptor(rng), b = RandomDescriptor(rng);
  const std::vector<Descriptor> data{a, b, a, a, b};
  const auto result = ClusterBinary(data, AllIndices(data.size()), {10, 10}, 1);
  EXPECT_EQ(result.centres.size(), 2u);
  const std::vector<Descriptor> same(7, a);
  EXPECT_EQ(ClusterBinary(same, AllIndices(same.size()), {10, 10}, 1).centres.size(), 1u);
}

TEST(ClusterBinary, RecoversWellSeparatedClustersAndConverges) {
  std::mt19937 rng(6);
  std::vector<Descriptor> data;
  std::vector<int> truth;
  for (int c = 0; c < 4; ++c) {
    const Descriptor centre = RandomDescriptor(rng);  // ~128 bits from the others
    for (int m = 0; m < 60; ++m) {
      data.push_back(FlipBits(centre, m % 6, rng));
      truth.push_back(c);
    }
  }
  const auto members = AllIndices(data.size());
  const auto result = ClusterBinary(data, members, {4, 20}, 42);
  ASSERT_EQ(result.centres.size(), 4u);
  EXPECT_LT(result.iterations, 20);
  for (std::size_t i = 0; i < data.size(); ++i) {
    for (std::size_t j = 0; j < data.size(); ++j) {
      ASSERT_EQ(truth[i] == truth[j], result.assignment[i] == result.assignment[j]) << i << " " << j;
    }
    // Converged: every member sits at its nearest centre, each centre the
    // majority of its members.
    ASSERT_EQ(result.assignment[i], NearestCentre(result.centres, data[i]));
  }
  for (std::uint32_t c = 0; c < 4; ++c) {
    std::vector<Descriptor> cluster;
    for (std::size_t i = 0; i < data.size(); ++i) {
      if (result.assignment[i] == c) cluster.push_back(data[i]);
    }
    EXPECT_EQ(result.centres[c], MajorityDescriptor(cluster));
  }
}

TEST(ClusterBinary, SubsetOfMembersAndDeterminism) {
  std::mt19937 rng(7);
  std::vector<Descriptor> data;
  for (int i = 0; i < 300; ++i) data.push_back(RandomDescriptor(rng));
  std::vector<std::uint32_t> members;
  for (std::uint32_t i = 0; i < data.size(); i += 3) members.push_back(i);
  const auto a = ClusterBinary(data, members, {8, 10}, 9);
  const auto b = ClusterBinary(data, members, {8, 10}, 9);
  EXPECT_EQ(a.centres, b.centres);
  EXPECT_EQ(a.assignment, b.assignment);
  EXPECT_EQ(a.assignment.size(), members.size());
}

TEST(ClusterBinary, RejectsBadOptions) {
  EXPECT_THROW(BinaryKMeansOptions({1, 10}).Check(), Error);
  EXPECT_THROW(BinaryKMeansOptions({256, 10}).Check(), Error);
  EXPECT_THROW(BinaryKMeansOptions({10, 0}).Check(), Error);
  EXPECT_TRUE(ClusterBinary({}, {}, {}, 0).centres.empty());
}

}  // namespace
}  // namespace dlslam::place

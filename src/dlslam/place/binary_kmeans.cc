#include "dlslam/place/binary_kmeans.h"

#include <array>
#include <cstring>

#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

int Distance(const Descriptor& a, const Descriptor& b) { return HammingDistance(a.data(), b.data()); }

// Uniform in [0, 1) from 53 random bits.
double UniformUnit(std::uint64_t& state) {
  return static_cast<double>(SplitMix64(state) >> 11) * 0x1.0p-53;
}

// kByteLanes[b] spreads the 8 bits of byte b over the 8 bytes of a uint64
// (bit i -> byte i), so one 64-bit add counts 8 bits at once.
constexpr std::array<std::uint64_t, 256> MakeByteLanes() {
  std::array<std::uint64_t, 256> lanes{};
  for (int b = 0; b < 256; ++b) {
    for (int bit = 0; bit < 8; ++bit) {
      if (b & (1 << bit)) lanes[b] |= std::uint64_t{1} << (8 * bit);
    }
  }
  return lanes;
}
constexpr std::array<std::uint64_t, 256> kByteLanes = MakeByteLanes();

// Counts, per bit, how many added descriptors have it set: 8-bit lanes
// accumulate up to 255 descriptors, then flush into 32-bit totals.
class BitCounter {
 public:
  void Add(const Descriptor& d) {
    for (int byte = 0; byte < 32; ++byte) lanes_[byte] += kByteLanes[d[byte]];
    if (++pending_ == 255) Flush();
    ++count_;
  }
  Descriptor Majority() {
    Flush();
    Descriptor out{};
    for (int bit = 0; bit < 256; ++bit) {
      if (2 * static_cast<std::int64_t>(totals_[bit]) > count_) {
        out[bit / 8] = static_cast<std::uint8_t>(out[bit / 8] | (1 << (bit % 8)));
      }
    }
    return out;
  }
  std::int64_t count() const { return count_; }

 private:
  void Flush() {
    for (int byte = 0; byte < 32; ++byte) {
      for (int bit = 0; bit < 8; ++bit) totals_[8 * byte + bit] += (lanes_[byte] >> (8 * bit)) & 0xFFu;
      lanes_[byte] = 0;
    }
    pending_ = 0;
  }
  std::array<std::uint64_t, 32> lanes_{};
  std::array<std::uint32_t, 256> totals_{};
  int pending_ = 0;
  std::int64_t count_ = 0;
};

// k-means++: the first centre uniformly, each next one with probability
// proportional to the squared distance to the nearest centre chosen so far.
std::vector<Descriptor> SeedCentres(std::span<const Descriptor> descriptors,
                                    std::span<const std::uint32_t> members, int k, std::uint64_t& rng) {
  const std::size_t n = members.size();
  std::vector<Descriptor> centres;
  std::size_t first = static_cast<std::size_t>(UniformUnit(rng) * static_cast<double>(n));
  centres.push_back(descriptors[members[std::min(first, n - 1)]]);
  std::vector<int> nearest(n);
  for (std::size_t i = 0; i < n; ++i) nearest[i] = Distance(descriptors[members[i]], centres[0]);
  while (static_cast<int>(centres.size()) < k) {
    double total = 0.0;
    for (int d : nearest) total += static_cast<double>(d) * d;
    if (total == 0.0) break;  // every member equals a centre: fewer distinct descriptors than k
    const double target = UniformUnit(rng) * total;
    double cumulative = 0.0;
    std::size_t pick = n - 1;
    for (std::size_t i = 0; i < n; ++i) {
      cumulative += static_cast<double>(nearest[i]) * nearest[i];
      if (cumulative > target && nearest[i] > 0) {
        pick = i;
        break;
      }
    }
    while (nearest[pick] == 0) --pick;  // rounding at the end: take the last non-zero one
    centres.push_back(descriptors[members[pick]]);
    for (std::size_t i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], Distance(descriptors[members[i]], centres.back()));
    }
  }
  return centres;
}

}  // namespace

void BinaryKMeansOptions::Check() const {
  DLSLAM_CHECK(k >= 2 && k <= 255, "k-means: k must be in [2, 255], got {}", k);
  DLSLAM_CHECK_GE(max_iterations, 1, "k-means: max_iterations must be at least 1");
}

std::uint64_t SplitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::uint32_t NearestCentre(std::span<const Descriptor> centres, const Descriptor& d) {
  std::uint32_t best = 0;
  int best_distance = 257;
  for (std::uint32_t c = 0; c < centres.size(); ++c) {
    const int distance = Distance(centres[c], d);
    if (distance < best_distance) {
      best_distance = distance;
      best = c;
    }
  }
  return best;
}

Descriptor MajorityDescriptor(std::span<const Descriptor> descriptors) {
  BitCounter counter;
  for (const Descriptor& d : descriptors) counter.Add(d);
  return counter.Majority();
}

BinaryKMeansResult ClusterBinary(std::span<const Descriptor> descriptors,
                                 std::span<const std::uint32_t> members,
                                 const BinaryKMeansOptions& options, std::uint64_t seed) {
  options.Check();
  BinaryKMeansResult result;
  if (members.empty()) return result;
  std::uint64_t rng = seed;
  result.centres = SeedCentres(descriptors, members, options.k, rng);
  result.assignment.assign(members.size(), 0);
  std::vector<BitCounter> counters;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    bool changed = iteration == 0;
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::uint32_t c = NearestCentre(result.centres, descriptors[members[i]]);
      changed |= c != result.assignment[i];
      result.assignment[i] = c;
    }
    result.iterations = iteration + 1;
    if (!changed) break;
    counters.assign(result.centres.size(), BitCounter());
    for (std::size_t i = 0; i < members.size(); ++i) counters[result.assignment[i]].Add(descriptors[members[i]]);
    // Empty clusters are dropped (renumbering the rest), so every centre
    // returned has members.
    std::vector<std::uint32_t> renumber(counters.size());
    std::vector<Descriptor> centres;
    for (std::size_t c = 0; c < counters.size(); ++c) {
      renumber[c] = static_cast<std::uint32_t>(centres.size());
      if (counters[c].count() > 0) centres.push_back(counters[c].Majority());
    }
    if (centres.size() != result.centres.size()) {
      for (std::uint32_t& a : result.assignment) a = renumber[a];
    }
    result.centres = std::move(centres);
  }
  return result;
}

}  // namespace dlslam::place

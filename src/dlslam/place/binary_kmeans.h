#pragma once
// k-means on 256-bit binary descriptors: k-means++ seeding, Hamming distance,
// bitwise-majority centres (the centre's bit is 1 when more than half of its
// members have it). One node of the vocabulary tree; the tree trainer calls
// it for every node.

#include <cstdint>
#include <span>
#include <vector>

#include "dlslam/map/map_types.h"

namespace dlslam::place {

struct BinaryKMeansOptions {
  int k = 10;               // clusters wanted [count, 2..255]
  int max_iterations = 15;  // Lloyd iterations after seeding, at most [count, >= 1]
  void Check() const;       // throws dlslam::Error with the values
};

struct BinaryKMeansResult {
  // At most k centres: fewer when the members hold fewer distinct
  // descriptors, or when a cluster ends up empty.
  std::vector<Descriptor> centres;
  // Per member (in the order of `members`): index into `centres`.
  std::vector<std::uint32_t> assignment;
  int iterations = 0;  // Lloyd iterations run
};

// Clusters descriptors[members[i]]. Deterministic in `seed` (own generator,
// the same on every platform). Stops when no assignment changes.
BinaryKMeansResult ClusterBinary(std::span<const Descriptor> descriptors,
                                 std::span<const std::uint32_t> members,
                                 const BinaryKMeansOptions& options, std::uint64_t seed);

// Index of the centre nearest to `d` (the first of equals).
std::uint32_t NearestCentre(std::span<const Descriptor> centres, const Descriptor& d);

// Bitwise majority of the descriptors (ties give 0); zeros when empty.
Descriptor MajorityDescriptor(std::span<const Descriptor> descriptors);

// SplitMix64: a small, portable generator step (seeds derived per tree node).
std::uint64_t SplitMix64(std::uint64_t& state);

}  // namespace dlslam::place

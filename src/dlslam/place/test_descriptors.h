#pragma once
// Synthetic binary descriptors for the place tests: random ones, noisy
// copies, and a two-level cluster hierarchy whose true tree is known.

#include <cstdint>
#include <random>
#include <vector>

#include "dlslam/map/map_types.h"
#include "dlslam/place/vocabulary_training.h"

namespace dlslam::place::testing {

Descriptor RandomDescriptor(std::mt19937& rng);
// `d` with `bits` distinct random bits flipped.
Descriptor FlipBits(const Descriptor& d, int bits, std::mt19937& rng);

// k parents (random, ~128 bits apart), k children per parent (parent with
// 12 bits flipped, so siblings are ~24 bits apart), members = child with up
// to 4 bits flipped. Clear enough that k-means++ separates the levels; it
// is still a random seeding, so the tests use fixed seeds.
struct Hierarchy {
  std::vector<Descriptor> children;          // k*k true leaf centres, child c has parent c / k
  std::vector<Descriptor> members;           // all members
  std::vector<int> child_of_member;          // true leaf per member
};
Hierarchy MakeHierarchy(int k, int members_per_child, std::mt19937& rng);

// One image per member chunk: image i holds members whose index % images == i.
TrainingDescriptors SplitIntoImages(const std::vector<Descriptor>& members, int images);

}  // namespace dlslam::place::testing

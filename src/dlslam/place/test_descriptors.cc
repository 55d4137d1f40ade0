#include "dlslam/place/test_descriptors.h"

#include <algorithm>
#include <numeric>

namespace dlslam::place::testing {

Descriptor RandomDescriptor(std::mt19937& rng) {
  Descriptor d;
  std::uniform_int_distribution<int> byte(0, 255);
  for (auto& b : d) b = static_cast<std::uint8_t>(byte(rng));
  return d;
}

Descriptor FlipBits(const Descriptor& d, int bits, std::mt19937& rng) {
  std::vector<int> positions(256);
  std::iota(positions.begin(), positions.end(), 0);
  std::shuffle(positions.begin(), positions.end(), rng);
  Descriptor out = d;
  for (int i = 0; i < bits; ++i) {
    out[positions[i] / 8] = static_cast<std::uint8_t>(out[positions[i] / 8] ^ (1 << (positions[i] % 8)));
  }
  return out;
}

Hierarchy MakeHierarchy(int k, int members_per_child, std::mt19937& rng) {
  Hierarchy h;
  std::uniform_int_distribution<int> noise(0, 4);
  for (int p = 0; p < k; ++p) {
    const Descriptor parent = RandomDescriptor(rng);
    for (int c = 0; c < k; ++c) {
      h.children.push_back(FlipBits(parent, 12, rng));
      for (int m = 0; m < members_per_child; ++m) {
        h.members.push_back(FlipBits(h.children.back(), noise(rng), rng));
        h.child_of_member.push_back(static_cast<int>(h.children.size()) - 1);
      }
    }
  }
  return h;
}

TrainingDescriptors SplitIntoImages(const std::vector<Descriptor>& members, int images) {
  TrainingDescriptors training;
  for (int i = 0; i < images; ++i) {
    std::vector<Descriptor> image;
    for (std::size_t m = static_cast<std::size_t>(i); m < members.size(); m += static_cast<std::size_t>(images)) {
      image.push_back(members[m]);
    }
    training.AddImage(image);
  }
  return training;
}

}  // namespace dlslam::place::testing

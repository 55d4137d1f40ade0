#include "dlslam/map/map_types.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "dlslam/util/check.h"

namespace dlslam {

Descriptor DescriptorOf(const Frame& frame, std::size_t keypoint) {
  DLSLAM_CHECK_EQ(frame.descriptors().cols, 32, "ORB descriptors are 32 bytes");
  Descriptor d;
  std::memcpy(d.data(), frame.descriptor(keypoint), d.size());
  return d;
}

int PredictOctave(double distance, double max_distance, const ScalePyramid& pyramid) {
  const double ratio = max_distance / std::max(distance, 1e-9);
  const int octave = static_cast<int>(std::ceil(std::log(ratio) / std::log(pyramid.scale_factor)));
  return std::clamp(octave, 0, pyramid.levels - 1);
}

}  // namespace dlslam

#include "dlslam/data/trajectory.h"

#include <algorithm>

namespace dlslam {

bool HasIncreasingTimestamps(const Trajectory& trajectory) {
  return std::adjacent_find(trajectory.begin(), trajectory.end(),
                            [](const StampedPose& a, const StampedPose& b) {
                              return !(a.timestamp < b.timestamp);
                            }) == trajectory.end();
}

}  // namespace dlslam

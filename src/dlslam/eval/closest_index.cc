#include "dlslam/eval/closest_index.h"

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::eval {

std::size_t FindClosestIndex(std::span<const double> sorted, double target) {
  DLSLAM_CHECK(!sorted.empty(), "closest index in an empty list");
  std::size_t begin = 0;
  std::size_t end = sorted.size();
  std::size_t best = 0;
  double best_diff = std::abs(sorted[0] - target);
  while (begin < end) {
    const std::size_t middle = (begin + end) / 2;
    const double diff = std::abs(sorted[middle] - target);
    if (diff < best_diff) {  // strict: the first probe of a tie wins
      best_diff = diff;
      best = middle;
    }
    if (sorted[middle] == target) return middle;
    if (sorted[middle] > target) {
      end = middle;
    } else {
      begin = middle + 1;
    }
  }
  return best;
}

}  // namespace dlslam::eval

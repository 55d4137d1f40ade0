#pragma once
// The TUM tools' find_closest_index: a binary search over sorted values that
// returns the closest of the elements it probed (not necessarily the closest
// overall when equal distances tie), or the exact hit as soon as it sees one.
// evaluate_rpe.py picks pose pairs and ground-truth stamps with it, so its
// tie-breaking is part of the metric.

#include <cstddef>
#include <span>

namespace dlslam::eval {

// `sorted` ascending and non-empty (throws dlslam::Error if empty).
std::size_t FindClosestIndex(std::span<const double> sorted, double target);

}  // namespace dlslam::eval

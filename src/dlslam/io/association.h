#pragma once
// Pairs two lists of timestamps (RGB and depth frames, or estimated and
// ground-truth poses) by nearest time, as the TUM RGB-D benchmark's
// associate.py does: every pair with |a - (b + offset)| < max_diff is a
// candidate; candidates are taken greedily by increasing difference (ties by
// a, then b), each timestamp at most once; the result is sorted by time.
// Pure function: no files.

#include <cstddef>
#include <utility>
#include <vector>

namespace dlslam::io {

// (index into the first list, index into the second list).
using IndexPair = std::pair<std::size_t, std::size_t>;

// `a`, `b`: timestamps [s], any order, finite. `offset` [s] is added to every
// b before comparing (associate.py --offset). `max_diff` [s] > 0 is the
// strict upper bound on the difference (associate.py --max_difference, 0.02).
// Returns index pairs sorted by (a[i], b[j]). O((n + m) log(n + m) + k log k)
// for k candidate pairs. Throws dlslam::Error on a non-finite input.
std::vector<IndexPair> AssociateTimestamps(const std::vector<double>& a,
                                           const std::vector<double>& b, double offset = 0.0,
                                           double max_diff = 0.02);

}  // namespace dlslam::io

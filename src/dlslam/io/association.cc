#include "dlslam/io/association.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

struct Candidate {
  double diff;
  std::size_t i;
  std::size_t j;
};

}  // namespace

std::vector<IndexPair> AssociateTimestamps(const std::vector<double>& a,
                                           const std::vector<double>& b, double offset,
                                           double max_diff) {
  DLSLAM_CHECK(std::isfinite(offset), "association offset {} must be finite", offset);
  DLSLAM_CHECK(std::isfinite(max_diff) && max_diff > 0,
               "association max_diff {} must be positive and finite", max_diff);
  for (double t : a) DLSLAM_CHECK(std::isfinite(t), "timestamp {} is not finite", t);
  for (double t : b) DLSLAM_CHECK(std::isfinite(t), "timestamp {} is not finite", t);

  // b + offset, computed exactly as the reference tool does, in sorted order.
  std::vector<double> shifted(b.size());
  for (std::size_t j = 0; j < b.size(); ++j) shifted[j] = b[j] + offset;
  std::vector<std::size_t> order(b.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return shifted[x] < shifted[y]; });
  std::vector<double> sorted_shifted(b.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted_shifted[k] = shifted[order[k]];

  // A window slightly wider than max_diff only adds candidates that the exact
  // test below rejects; it never loses one to rounding.
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double margin = max_diff * (1 + 1e-9) + 1e-12 * std::abs(a[i]);
    auto it = std::lower_bound(sorted_shifted.begin(), sorted_shifted.end(), a[i] - margin);
    for (; it != sorted_shifted.end() && *it <= a[i] + margin; ++it) {
      const std::size_t j = order[static_cast<std::size_t>(it - sorted_shifted.begin())];
      const double diff = std::abs(a[i] - shifted[j]);
      if (diff < max_diff) candidates.push_back({diff, i, j});
    }
  }
  // (diff, a, b) as the reference tool's tuple sort; indices break exact ties
  // between duplicate timestamps deterministically.
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& x, const Candidate& y) {
    return std::tie(x.diff, a[x.i], b[x.j], x.i, x.j) < std::tie(y.diff, a[y.i], b[y.j], y.i, y.j);
  });

  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  std::vector<IndexPair> pairs;
  for (const Candidate& c : candidates) {
    if (used_a[c.i] || used_b[c.j]) continue;
    used_a[c.i] = used_b[c.j] = true;
    pairs.push_back({c.i, c.j});
  }
  std::sort(pairs.begin(), pairs.end(), [&](const IndexPair& x, const IndexPair& y) {
    return std::tie(a[x.first], b[x.second], x.first, x.second) <
           std::tie(a[y.first], b[y.second], y.first, y.second);
  });
  return pairs;
}

}  // namespace dlslam::io

#include "dlslam/eval/stats.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::eval {

double Median(std::span<const double> values) {
  DLSLAM_CHECK(!values.empty(), "median of no values");
  std::vector<double> v(values.begin(), values.end());
  const std::size_t half = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(half), v.end());
  const double upper = v[half];
  if (v.size() % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(half));
  return (lower + upper) / 2.0;
}

ErrorStats ComputeErrorStats(std::span<const double> errors) {
  DLSLAM_CHECK(!errors.empty(), "statistics of no errors");
  const double n = static_cast<double>(errors.size());
  ErrorStats s;
  double sum = 0.0;
  double sum_sq = 0.0;
  for (const double e : errors) {
    sum += e;
    sum_sq += e * e;
  }
  s.rmse = std::sqrt(sum_sq / n);
  s.mean = sum / n;
  // Two passes (not sum_sq/n - mean^2), which cancels badly for small spreads.
  double var = 0.0;
  for (const double e : errors) var += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(var / n);
  s.median = Median(errors);
  const auto [lo, hi] = std::minmax_element(errors.begin(), errors.end());
  s.min = *lo;
  s.max = *hi;
  return s;
}

}  // namespace dlslam::eval

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
  return lower + (upper - lower) / 2.0;  // no overflow near the largest doubles
}

ErrorStats ComputeErrorStats(std::span<const double> errors) {
  DLSLAM_CHECK(!errors.empty(), "statistics of no errors");
  const double n = static_cast<double>(errors.size());
  ErrorStats s;
  const auto [lo, hi] = std::minmax_element(errors.begin(), errors.end());
  s.min = *lo;
  s.max = *hi;
  // Scaled by the largest magnitude, so that neither the squares nor the
  // sums overflow (errors of 1e200 m give an RMSE of 1e200, not inf).
  const double scale = std::max(std::abs(s.min), std::abs(s.max));
  double sum = 0.0;
  double sum_sq = 0.0;
  if (scale > 0 && std::isfinite(scale)) {
    for (const double e : errors) {
      sum += e / scale;
      sum_sq += (e / scale) * (e / scale);
    }
  }
  s.rmse = scale > 0 ? scale * std::sqrt(sum_sq / n) : 0.0;
  s.mean = scale > 0 ? scale * (sum / n) : 0.0;
  // Two passes (not sum_sq/n - mean^2), which cancels badly for small spreads.
  double var = 0.0;
  if (scale > 0 && std::isfinite(scale)) {
    for (const double e : errors) var += ((e - s.mean) / scale) * ((e - s.mean) / scale);
  }
  s.std = scale * std::sqrt(var / n);
  s.median = Median(errors);
  return s;
}

}  // namespace dlslam::eval

#pragma once
// Summary statistics of per-pair errors, computed as numpy does in the TUM
// tools: median averages the two middle values of an even count, std is the
// population standard deviation (numpy.std, ddof = 0).

#include <cstddef>
#include <span>

namespace dlslam::eval {

struct ErrorStats {
  double rmse = 0.0;    // sqrt(sum e^2 / n)
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;     // population standard deviation
  double min = 0.0;
  double max = 0.0;
};

// Throws dlslam::Error for an empty span.
ErrorStats ComputeErrorStats(std::span<const double> errors);

// Median of values (copied, then partially sorted); throws for an empty span.
double Median(std::span<const double> values);

}  // namespace dlslam::eval

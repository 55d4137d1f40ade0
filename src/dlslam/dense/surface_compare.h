#pragma once
// How close a reconstructed surface is to a reference one (a synthetic
// room, a laser scan), both as point samples in the same frame:
//   accuracy      distance of each model point to the nearest reference
//                 point (median, mean, 90th percentile)
//   completeness  share of reference points with a model point within
//                 `radius`
// Nearest neighbours through a hash grid of `radius`-sized cells; distances
// beyond `radius` are counted at their true value only up to 3 * radius
// (clamped), which keeps outliers from dominating the mean.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace dlslam::dense {

struct SurfaceComparison {
  std::size_t model_points = 0;
  std::size_t reference_points = 0;
  double accuracy_median = 0.0;  // [m]
  double accuracy_mean = 0.0;    // [m]
  double accuracy_p90 = 0.0;     // [m]
  double completeness = 0.0;     // [0, 1]
};

// Throws dlslam::Error for radius <= 0. Empty inputs give zeros.
SurfaceComparison CompareSurfaces(const std::vector<Eigen::Vector3f>& model,
                                  const std::vector<Eigen::Vector3f>& reference, double radius);

}  // namespace dlslam::dense

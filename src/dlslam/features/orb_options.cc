#include "dlslam/features/orb_options.h"

#include <algorithm>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::features {

void OrbOptions::Check() const {
  DLSLAM_CHECK_GT(n_features, 0, "OrbOptions::n_features");
  DLSLAM_CHECK(n_levels >= 1 && n_levels <= 32, "OrbOptions::n_levels {} outside [1, 32]",
               n_levels);
  DLSLAM_CHECK(scale_factor > 1.0 && scale_factor <= 4.0,
               "OrbOptions::scale_factor {} outside (1, 4]", scale_factor);
  DLSLAM_CHECK(fast_threshold_initial >= 1 && fast_threshold_initial <= 254,
               "OrbOptions::fast_threshold_initial {} outside [1, 254]", fast_threshold_initial);
  DLSLAM_CHECK(fast_threshold_min >= 1 && fast_threshold_min <= fast_threshold_initial,
               "OrbOptions::fast_threshold_min {} outside [1, fast_threshold_initial = {}]",
               fast_threshold_min, fast_threshold_initial);
  DLSLAM_CHECK(cell_size >= 8 && cell_size <= 1000, "OrbOptions::cell_size {} outside [8, 1000]",
               cell_size);
  DLSLAM_CHECK(edge_border >= kPatchRadius + 1 && edge_border <= 100,
               "OrbOptions::edge_border {} outside [{}, 100]", edge_border, kPatchRadius + 1);
  DLSLAM_CHECK(exclusion_radius >= 0 && exclusion_radius <= kPatchRadius,
               "OrbOptions::exclusion_radius {} outside [0, {}]", exclusion_radius, kPatchRadius);
}

std::vector<double> LevelScales(const OrbOptions& options) {
  std::vector<double> scales(static_cast<size_t>(options.n_levels));
  double scale = 1.0;
  for (double& s : scales) {
    s = scale;
    scale *= options.scale_factor;
  }
  return scales;
}

std::vector<int> LevelFeatureTargets(const OrbOptions& options) {
  const int n = options.n_levels;
  const double ratio = 1.0 / options.scale_factor;
  // First term of a geometric series with n terms summing to n_features.
  double wanted = options.n_features * (1.0 - ratio) / (1.0 - std::pow(ratio, n));
  std::vector<int> targets(static_cast<size_t>(n));
  int assigned = 0;
  for (int level = 0; level + 1 < n; ++level) {
    targets[static_cast<size_t>(level)] =
        std::min(static_cast<int>(std::lround(wanted)), options.n_features - assigned);
    assigned += targets[static_cast<size_t>(level)];
    wanted *= ratio;
  }
  // The coarsest level takes the rounding remainder so the total is exact.
  targets[static_cast<size_t>(n - 1)] = std::max(0, options.n_features - assigned);
  return targets;
}

}  // namespace dlslam::features

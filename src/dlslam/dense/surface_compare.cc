#include "dlslam/dense/surface_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "dlslam/util/check.h"

namespace dlslam::dense {

namespace {

class HashGrid {
 public:
  HashGrid(const std::vector<Eigen::Vector3f>& points, double cell) : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) cells_[Key(Cell(points[i]))].push_back(static_cast<int>(i));
  }

  // Distance to the nearest point, searched in the 27 cells around `p`;
  // `limit` when none is there.
  double Nearest(const Eigen::Vector3f& p, double limit) const {
    const Eigen::Vector3i c = Cell(p);
    double best = limit * limit;
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(Key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int i : it->second) best = std::min(best, static_cast<double>((points_[static_cast<std::size_t>(i)] - p).squaredNorm()));
        }
      }
    }
    return std::sqrt(best);
  }

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3f& p) const {
    return {static_cast<int>(std::floor(p.x() / cell_)), static_cast<int>(std::floor(p.y() / cell_)),
            static_cast<int>(std::floor(p.z() / cell_))};
  }
  static std::int64_t Key(const Eigen::Vector3i& c) {
    return (static_cast<std::int64_t>(c.x() & 0x1fffff)) | (static_cast<std::int64_t>(c.y() & 0x1fffff) << 21) |
           (static_cast<std::int64_t>(c.z() & 0x1fffff) << 42);
  }

  const std::vector<Eigen::Vector3f>& points_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

}  // namespace

SurfaceComparison CompareSurfaces(const std::vector<Eigen::Vector3f>& model,
                                  const std::vector<Eigen::Vector3f>& reference, double radius) {
  DLSLAM_CHECK(radius > 0, "CompareSurfaces: radius {} must be > 0", radius);
  SurfaceComparison out;
  out.model_points = model.size();
  out.reference_points = reference.size();
  if (model.empty() || reference.empty()) return out;
  const double limit = 3 * radius;
  // Cells of `limit`: the 27-cell search then finds every neighbour within it.
  const HashGrid reference_grid(reference, limit);
  std::vector<double> distances;
  distances.reserve(model.size());
  for (const Eigen::Vector3f& p : model) distances.push_back(reference_grid.Nearest(p, limit));
  double sum = 0;
  for (double d : distances) sum += d;
  out.accuracy_mean = sum / static_cast<double>(distances.size());
  const auto quantile = [&distances](double q) {
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(distances.size() - 1));
    std::nth_element(distances.begin(), distances.begin() + k, distances.end());
    return distances[static_cast<std::size_t>(k)];
  };
  out.accuracy_median = quantile(0.5);
  out.accuracy_p90 = quantile(0.9);
  const HashGrid model_grid(model, radius);
  std::size_t covered = 0;
  for (const Eigen::Vector3f& r : reference) covered += model_grid.Nearest(r, radius) < radius;
  out.completeness = static_cast<double>(covered) / static_cast<double>(reference.size());
  return out;
}

}  // namespace dlslam::dense

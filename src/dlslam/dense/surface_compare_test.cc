#include "dlslam/dense/surface_compare.h"

#include <gtest/gtest.h>

namespace dlslam::dense {
namespace {

std::vector<Eigen::Vector3f> Grid(float z, int n, float step) {
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) points.emplace_back(i * step, j * step, z);
  }
  return points;
}

TEST(CompareSurfaces, AShiftedCopyIsAsFarAsTheShift) {
  const std::vector<Eigen::Vector3f> reference = Grid(0.0f, 50, 0.01f);
  const SurfaceComparison same = CompareSurfaces(reference, reference, 0.02);
  EXPECT_EQ(same.accuracy_median, 0.0);
  EXPECT_EQ(same.completeness, 1.0);
  const SurfaceComparison shifted = CompareSurfaces(Grid(0.005f, 50, 0.01f), reference, 0.02);
  EXPECT_NEAR(shifted.accuracy_median, 0.005, 1e-6);
  EXPECT_NEAR(shifted.accuracy_p90, 0.005, 1e-6);
  EXPECT_EQ(shifted.completeness, 1.0);
}

TEST(CompareSurfaces, HalfAModelIsHalfComplete) {
  const std::vector<Eigen::Vector3f> reference = Grid(0.0f, 40, 0.01f);
  std::vector<Eigen::Vector3f> half;
  for (const Eigen::Vector3f& p : reference) {
    if (p.x() < 0.195f) half.push_back(p);
  }
  const SurfaceComparison c = CompareSurfaces(half, reference, 0.005);
  EXPECT_NEAR(c.completeness, 0.5, 0.01);
  EXPECT_EQ(c.accuracy_mean, 0.0);
  // An outlier 1 m away counts at the clamp, 3 radii.
  half.emplace_back(0.0f, 0.0f, 1.0f);
  EXPECT_NEAR(CompareSurfaces(half, reference, 0.005).accuracy_mean, 0.015 / static_cast<double>(half.size()), 1e-9);
}

}  // namespace
}  // namespace dlslam::dense

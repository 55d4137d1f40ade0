#include "dlslam/optimize/rigid_ransac.h"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <random>

#include "dlslam/eval/horn.h"
#include "dlslam/util/check.h"

namespace dlslam {

void RigidRansacOptions::Check() const {
  DLSLAM_CHECK_GT(max_iterations, 0, "rigid RANSAC max_iterations");
  DLSLAM_CHECK(confidence > 0 && confidence < 1, "rigid RANSAC confidence {} outside (0, 1)", confidence);
  DLSLAM_CHECK_GE(min_inliers, 3, "rigid RANSAC min_inliers");
}

namespace {

// A triangle too thin to fix a rotation: its points (nearly) coincide or lie
// on a line. Judged by its height over its longest side (|e1 x e2| / L^2),
// which does not depend on the units.
bool Degenerate(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e1 = p1 - p0;
  const Eigen::Vector3d e2 = p2 - p0;
  const Eigen::Vector3d e3 = p2 - p1;
  const double longest_sq = std::max({e1.squaredNorm(), e2.squaredNorm(), e3.squaredNorm()});
  if (longest_sq < 1e-12) return true;  // all within a micrometre
  return e1.cross(e2).norm() < 1e-3 * longest_sq;
}

SE3d ToSe3(const eval::RigidAlignment& alignment) {
  return SE3d(SO3d(alignment.rotation), alignment.translation);
}

int CountInliers(const SE3d& b_from_a, std::span<const Eigen::Vector3d> a, std::span<const Eigen::Vector3d> b,
                 std::span<const double> max_error, std::vector<bool>* inliers) {
  int count = 0;
  if (inliers != nullptr) inliers->assign(a.size(), false);
  const Eigen::Matrix3d rotation = b_from_a.rotationMatrix();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool inlier = (rotation * a[i] + b_from_a.translation() - b[i]).squaredNorm() <= max_error[i] * max_error[i];
    count += inlier;
    if (inliers != nullptr) (*inliers)[i] = inlier;
  }
  return count;
}

// Samples needed to draw one all-inlier triple with `confidence`, given the inlier ratio.
double NeededIterations(double inlier_ratio, double confidence) {
  const double all_inlier = inlier_ratio * inlier_ratio * inlier_ratio;
  if (all_inlier >= 1.0) return 1.0;
  if (all_inlier <= 0.0) return INFINITY;
  return std::log(1 - confidence) / std::log(1 - all_inlier);
}

}  // namespace

std::optional<RigidRansacResult> EstimateRigidRansac(std::span<const Eigen::Vector3d> a,
                                                     std::span<const Eigen::Vector3d> b,
                                                     std::span<const double> max_error,
                                                     const RigidRansacOptions& options, std::uint32_t seed) {
  options.Check();
  DLSLAM_CHECK_EQ(a.size(), b.size(), "rigid RANSAC: point sets differ in size");
  DLSLAM_CHECK_EQ(a.size(), max_error.size(), "rigid RANSAC: one max_error per correspondence");
  for (std::size_t i = 0; i < max_error.size(); ++i) {
    DLSLAM_CHECK(std::isfinite(max_error[i]) && max_error[i] >= 0,
                 "rigid RANSAC: max_error[{}] = {} must be finite and >= 0", i, max_error[i]);
  }
  const int n = static_cast<int>(a.size());
  if (n < 3 || n < options.min_inliers) return std::nullopt;

  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  RigidRansacResult result;
  int best = 0;
  std::array<Eigen::Vector3d, 3> sample_a, sample_b;
  while (result.iterations < options.max_iterations) {
    ++result.iterations;
    const int i0 = pick(rng);
    int i1 = pick(rng);
    while (i1 == i0) i1 = pick(rng);
    int i2 = pick(rng);
    while (i2 == i0 || i2 == i1) i2 = pick(rng);
    sample_a = {a[i0], a[i1], a[i2]};
    sample_b = {b[i0], b[i1], b[i2]};
    if (Degenerate(sample_a[0], sample_a[1], sample_a[2])) continue;
    if (Degenerate(sample_b[0], sample_b[1], sample_b[2])) continue;
    const SE3d model = ToSe3(eval::AlignHorn(sample_a, sample_b));
    const int count = CountInliers(model, a, b, max_error, nullptr);
    if (count > best) {
      best = count;
      result.b_from_a = model;
    }
    if (best > 0 && result.iterations >= NeededIterations(static_cast<double>(best) / n, options.confidence)) break;
  }
  if (best < options.min_inliers) return std::nullopt;

  // Refit on every inlier of the best sample (its three points fit exactly,
  // the rest are what the refit averages over).
  result.num_inliers = CountInliers(result.b_from_a, a, b, max_error, &result.inliers);
  std::vector<Eigen::Vector3d> inlier_a, inlier_b;
  for (int i = 0; i < n; ++i) {
    if (!result.inliers[i]) continue;
    inlier_a.push_back(a[i]);
    inlier_b.push_back(b[i]);
  }
  const SE3d refit = ToSe3(eval::AlignHorn(inlier_a, inlier_b));
  std::vector<bool> refit_inliers;
  const int refit_count = CountInliers(refit, a, b, max_error, &refit_inliers);
  if (refit_count >= result.num_inliers) {
    result.b_from_a = refit;
    result.inliers = std::move(refit_inliers);
    result.num_inliers = refit_count;
  }
  if (result.num_inliers < options.min_inliers) return std::nullopt;
  return result;
}

}  // namespace dlslam

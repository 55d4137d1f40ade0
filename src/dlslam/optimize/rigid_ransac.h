#pragma once
// Rigid transform between two sets of corresponding 3D points with RANSAC
// (a loop candidate: the current keyframe's map points against the loop
// keyframe's). RGB-D fixes the scale, so the model is SE(3), not Sim(3).
// Minimal samples of 3 correspondences; each fit is eval::AlignHorn.

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dlslam/geometry/se3.h"

namespace dlslam {

struct RigidRansacOptions {
  // Samples drawn at most (degenerate ones count too, so the loop always ends).
  int max_iterations = 300;
  // Stop early once a sample free of outliers has been drawn with this
  // probability, judged by the best inlier ratio so far; in (0, 1).
  double confidence = 0.99;
  // Fewer inliers than this (after the final refit) is no transform; >= 3.
  int min_inliers = 20;

  void Check() const;
};

struct RigidRansacResult {
  SE3d b_from_a;              // b_i ~ b_from_a * a_i
  std::vector<bool> inliers;  // per correspondence
  int num_inliers = 0;
  int iterations = 0;         // samples drawn
};

// Correspondence i is an inlier when ||b_from_a * a[i] - b[i]|| <= max_error[i]
// [m]. The best sample's model is refitted on all its inliers and the inliers
// are counted again (the refit is kept only if it keeps at least as many).
// nullopt when fewer than options.min_inliers remain, or when there are fewer
// than 3 correspondences or every sample is degenerate (coincident or
// collinear points). Throws dlslam::Error when the spans differ in size or a
// max_error is negative or not finite. Deterministic for a given seed.
std::optional<RigidRansacResult> EstimateRigidRansac(std::span<const Eigen::Vector3d> a,
                                                     std::span<const Eigen::Vector3d> b,
                                                     std::span<const double> max_error,
                                                     const RigidRansacOptions& options, std::uint32_t seed);

}  // namespace dlslam

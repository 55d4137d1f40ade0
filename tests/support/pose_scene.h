#pragma once
// A camera looking at random points 1-5 m away, as motion-only pose
// optimisation sees them: four pyramid levels, four in five keypoints with
// the RGB-D virtual right coordinate, a share of wrong matches (random
// pixels). Header-only so that tests and benchmarks share it.

#include <cmath>
#include <random>
#include <vector>

#include "dlslam/optimize/pose_optimizer.h"

namespace dlslam::testing {

struct PoseScene {
  CameraIntrinsics camera = CameraPreset("freiburg3");
  SE3d cam_from_world;
  std::vector<PoseObservation> observations;
  std::vector<bool> is_outlier;
};

inline PoseScene MakePoseScene(int n, double outlier_fraction, double pixel_noise, unsigned seed) {
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  PoseScene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  std::normal_distribution<double> noise(0, pixel_noise);
  Vector6d xi;
  xi << 0.3, -0.1, 0.5, 0.2, -0.3, 0.1;
  s.cam_from_world = SE3d::Exp(xi);
  const SE3d world_from_cam = s.cam_from_world.Inverse();
  for (int i = 0; i < n; ++i) {
    const double z = 1 + 4 * uni(rng);
    const Eigen::Vector2d px(uni(rng) * 640, uni(rng) * 480);
    PoseObservation o;
    o.point_world = world_from_cam * s.camera.Unproject(px, z);
    const int octave = static_cast<int>(uni(rng) * 4);
    const double sigma = std::pow(1.2, octave);
    o.information = 1.0 / (sigma * sigma);
    o.pixel = px + Eigen::Vector2d(noise(rng), noise(rng)) * sigma;
    const bool with_depth = uni(rng) < 0.8;
    o.right_u = with_depth ? o.pixel.x() - s.camera.bf / z + noise(rng) * sigma : -1.0;
    const bool outlier = uni(rng) < outlier_fraction;
    if (outlier) o.pixel = Eigen::Vector2d(uni(rng) * 640, uni(rng) * 480);
    if (outlier && with_depth) o.right_u = o.pixel.x() - s.camera.bf / z;
    s.observations.push_back(o);
    s.is_outlier.push_back(outlier);
  }
  return s;
}

// The pose moved by trans [m] and rot [rad] on every axis (signs mixed).
inline SE3d PerturbPose(const SE3d& pose, double trans, double rot) {
  Eigen::Matrix<double, 6, 1> d;
  d << trans, -trans, trans / 2, rot, rot / 2, -rot;
  return SE3d::Exp(d) * pose;
}

}  // namespace dlslam::testing

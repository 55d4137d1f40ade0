#pragma once
// A synthetic bundle-adjustment problem shaped like a local bundle of the
// SLAM core: keyframes along a path, the first ones fixed, points 1.5-6 m
// ahead, each seen by the keyframes near the one it was created in, two in
// three with the RGB-D virtual right coordinate. Header-only so that tests
// and benchmarks share it.

#include <random>
#include <vector>

#include "dlslam/optimize/bundle_adjuster.h"

namespace dlslam::testing {

struct SyntheticBundleOptions {
  int poses = 20;
  int fixed_poses = 5;       // the first ones
  int points = 4000;
  int view_window = 2;       // a point is seen by keyframes within this many of its own
  double pixel_noise = 0.5;  // [px], on u, v and right u
  double outlier_fraction = 0.0;
  double pose_perturbation = 0.01;    // initial error of free poses [rad, m]
  double point_perturbation = 0.02;   // initial error of points [m]
  unsigned seed = 1;
};

struct SyntheticBundle {
  BundleProblem problem;
  std::vector<SE3d> true_poses;
  std::vector<Eigen::Vector3d> true_points;
  std::vector<bool> is_outlier;  // per observation
};

inline SyntheticBundle MakeSyntheticBundle(const SyntheticBundleOptions& o) {
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  SyntheticBundle s;
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> n(0, 1);
  s.problem.camera = CameraPreset("freiburg3");
  for (int i = 0; i < o.poses; ++i) {
    Vector6d xi;
    xi << -0.05 * i, 0.01 * i, 0.02 * i, 0.005 * i, 0.02 * i, 0.003 * i;
    s.true_poses.push_back(SE3d::Exp(xi));
    BundleProblem::Pose pose;
    pose.fixed = i < o.fixed_poses;
    Vector6d d;
    for (int k = 0; k < 6; ++k) d[k] = pose.fixed ? 0 : o.pose_perturbation * n(rng);
    pose.cam_from_world = SE3d::Exp(d) * s.true_poses[i];
    s.problem.poses.push_back(pose);
  }
  for (int j = 0; j < o.points; ++j) {
    const int home = j % o.poses;
    const Eigen::Vector3d in_cam(-2.0 + 4 * u(rng), -1.5 + 3 * u(rng), 1.5 + 4.5 * u(rng));
    s.true_points.push_back(s.true_poses[home].Inverse() * in_cam);
    s.problem.points.push_back(s.true_points.back() + o.point_perturbation * Eigen::Vector3d(n(rng), n(rng), n(rng)));
    for (int i = std::max(0, home - o.view_window); i <= std::min(o.poses - 1, home + o.view_window); ++i) {
      const Eigen::Vector3d pc = s.true_poses[i] * s.true_points[j];
      if (pc.z() < 0.5) continue;
      const Eigen::Vector2d uv = s.problem.camera.Project(pc);
      if (uv.x() < 0 || uv.y() < 0 || uv.x() >= 640 || uv.y() >= 480) continue;
      BundleProblem::Observation ob;
      ob.pose = i;
      ob.point = j;
      const int octave = static_cast<int>(u(rng) * 4);
      const double sigma = std::pow(1.2, octave);
      ob.information = 1.0 / (sigma * sigma);
      ob.pixel = uv + sigma * o.pixel_noise * Eigen::Vector2d(n(rng), n(rng));
      ob.right_u = (j % 3 == 0) ? -1.0 : uv.x() - s.problem.camera.bf / pc.z() + sigma * o.pixel_noise * n(rng);
      const bool outlier = u(rng) < o.outlier_fraction;
      if (outlier) ob.pixel += Eigen::Vector2d(20 + 30 * u(rng), -25);
      s.problem.observations.push_back(ob);
      s.is_outlier.push_back(outlier);
    }
  }
  return s;
}

}  // namespace dlslam::testing

#include "tests/support/landmark_scene.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dlslam::testing {

LandmarkScene LandmarkScene::Room(int n, unsigned seed) {
  LandmarkScene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int i = 0; i < n; ++i) {
    const double a = u(rng), b = u(rng);
    Eigen::Vector3d p;
    switch (i % 5) {
      case 0: p = {-3 + 6 * a, -2 + 4 * b, 5}; break;   // far wall
      case 1: p = {-3, -2 + 4 * a, -1 + 6 * b}; break;  // left wall
      case 2: p = {3, -2 + 4 * a, -1 + 6 * b}; break;   // right wall
      case 3: p = {-3 + 6 * a, 2, -1 + 6 * b}; break;   // floor (y down)
      default: p = {-3 + 6 * a, -2 + 4 * b, 2.5 + u(rng)}; break;  // furniture in the middle
    }
    s.points.push_back(p);
    std::array<uint8_t, 32> d;
    for (auto& x : d) x = static_cast<uint8_t>(byte(rng));
    s.descriptors.push_back(d);
  }
  return s;
}

std::shared_ptr<Frame> LandmarkScene::MakeFrame(const SE3d& cam_from_world, double timestamp, unsigned seed,
                                                double pixel_noise, int bit_flips,
                                                std::vector<int>* landmark_of) const {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, pixel_noise);
  std::uniform_int_distribution<int> bit(0, 255);
  std::vector<int> visible;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d pc = cam_from_world * points[i];
    if (pc.z() < 0.3 || pc.z() > 8) continue;
    const Eigen::Vector2d uv = camera.Project(pc);
    if (uv.x() < 1 || uv.y() < 1 || uv.x() > camera.width - 2 || uv.y() > camera.height - 2) continue;
    visible.push_back(static_cast<int>(i));
  }
  std::shuffle(visible.begin(), visible.end(), rng);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat desc(static_cast<int>(visible.size()), 32, CV_8UC1);
  cv::Mat depth(camera.height, camera.width, CV_32FC1, cv::Scalar(0.f));
  for (std::size_t k = 0; k < visible.size(); ++k) {
    const int i = visible[k];
    const Eigen::Vector3d pc = cam_from_world * points[i];
    const Eigen::Vector2d uv = camera.Project(pc) + Eigen::Vector2d(noise(rng), noise(rng));
    const float x = std::clamp(static_cast<float>(uv.x()), 0.f, camera.width - 1.f);
    const float y = std::clamp(static_cast<float>(uv.y()), 0.f, camera.height - 1.f);
    keypoints.emplace_back(x, y, 31.f, 0.f, 1.f, 0);
    depth.at<float>(static_cast<int>(std::lround(y)), static_cast<int>(std::lround(x))) = static_cast<float>(pc.z());
    std::array<uint8_t, 32> d = descriptors[i];
    for (int f = 0; f < bit_flips; ++f) {
      const int b = bit(rng);
      d[b / 8] ^= static_cast<uint8_t>(1u << (b % 8));
    }
    std::copy(d.begin(), d.end(), desc.ptr<uint8_t>(static_cast<int>(k)));
  }
  if (landmark_of) *landmark_of = visible;
  return std::make_shared<Frame>(Frame::Create(timestamp, keypoints, desc, depth, camera, pyramid, 0.1, max_depth));
}

SE3d SmoothRoomPath(int i) {
  const double t = i / 30.0;
  Eigen::Matrix<double, 6, 1> xi;  // world_from_cam's tangent
  xi << 0.4 * std::sin(0.8 * t), 0.1 * std::sin(1.3 * t), 0.3 * std::sin(0.5 * t), 0.05 * std::sin(0.7 * t),
      0.25 * std::sin(0.6 * t), 0.03 * std::sin(t);
  return SE3d::Exp(xi).Inverse();
}

}  // namespace dlslam::testing

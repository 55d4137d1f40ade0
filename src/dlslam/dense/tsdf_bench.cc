// TSDF fusion of 640x480 depth: one keyframe into a volume that already
// holds a room's worth of blocks, and surface extraction.

#include <benchmark/benchmark.h>

#include "dlslam/dense/tsdf_volume.h"

namespace dlslam::dense {
namespace {

// A box room 4 x 3 x 5 m around the camera, seen from its centre.
cv::Mat RoomDepth(const CameraIntrinsics& camera, double yaw) {
  cv::Mat depth(camera.height, camera.width, CV_32FC1);
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray_cam((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
      const Eigen::Vector3d ray(c * ray_cam.x() + s * ray_cam.z(), ray_cam.y(), -s * ray_cam.x() + c * ray_cam.z());
      double t = 1e9;
      const double half[3] = {2.0, 1.5, 2.5};
      for (int a = 0; a < 3; ++a) {
        if (std::abs(ray[a]) > 1e-9) t = std::min(t, half[a] / std::abs(ray[a]));
      }
      depth.at<float>(v, u) = static_cast<float>(t);  // z of a ray with ray_cam.z = 1
    }
  }
  return depth;
}

SE3d CamFromWorld(double yaw) { return SE3d(SO3d::Exp(Eigen::Vector3d(0, yaw, 0)), Eigen::Vector3d::Zero()).Inverse(); }

void BM_TsdfIntegrate(benchmark::State& state) {
  const CameraIntrinsics camera;  // 640x480
  TsdfVolume volume(camera);
  for (int k = 0; k < 8; ++k) volume.Integrate(CamFromWorld(k * 0.8), RoomDepth(camera, k * 0.8), cv::Mat());
  const cv::Mat depth = RoomDepth(camera, 0.3);
  for (auto _ : state) volume.Integrate(CamFromWorld(0.3), depth, cv::Mat());
  state.counters["blocks"] = static_cast<double>(volume.NumBlocks());
}
BENCHMARK(BM_TsdfIntegrate)->Unit(benchmark::kMillisecond);

void BM_TsdfExtract(benchmark::State& state) {
  const CameraIntrinsics camera;
  TsdfVolume volume(camera);
  for (int k = 0; k < 16; ++k) volume.Integrate(CamFromWorld(k * 0.4), RoomDepth(camera, k * 0.4), cv::Mat());
  std::size_t points = 0;
  for (auto _ : state) points = volume.ExtractSurface().size();
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_TsdfExtract)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dlslam::dense

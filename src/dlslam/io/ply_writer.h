#pragma once
// Coloured point clouds as binary little-endian PLY (x y z as float, red
// green blue as uchar), which MeshLab, CloudCompare, Open3D and Blender read.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace dlslam::io {

struct ColouredPoint {
  Eigen::Vector3f position;
  std::array<std::uint8_t, 3> rgb;
};

// Written atomically (a failure keeps any old file); throws InputError.
void WritePointCloudPly(const std::filesystem::path& path, const std::vector<ColouredPoint>& points);

}  // namespace dlslam::io

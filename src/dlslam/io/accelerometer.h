#pragma once
// accelerometer.txt of the TUM RGB-D sequences: "timestamp ax ay az" per
// line [s, m/s^2], '#' comments (Kinect accelerometer, sensor frame).

#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace dlslam::io {

struct AccelerometerSample {
  double timestamp = 0.0;                                  // [s]
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // [m/s^2]
};

// Throws InputError (file:line) for a missing file, a line that is not four
// finite numbers, or a timestamp not larger than the one before.
std::vector<AccelerometerSample> ReadAccelerometer(const std::filesystem::path& path);

}  // namespace dlslam::io

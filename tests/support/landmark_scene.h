#pragma once
// A scene of 3D landmarks with random ORB-like descriptors, and frames made
// by projecting them: tests tracking logic without rendering images.

#include <opencv2/core.hpp>

#include <memory>
#include <random>
#include <vector>

#include "dlslam/data/frame.h"

namespace dlslam::testing {

struct LandmarkScene {
  std::vector<Eigen::Vector3d> points;            // world [m]
  std::vector<std::array<uint8_t, 32>> descriptors;
  CameraIntrinsics camera = CameraPreset("freiburg3");
  ScalePyramid pyramid;
  // Keypoints farther than this [m] get no depth (a sensor's range).
  double max_depth = 20.0;

  // Landmarks on the walls of a box room [-3,3] x [-2,2] x [-1,5] (camera near the origin looks along +z).
  static LandmarkScene Room(int n, unsigned seed);

  // The frame seen from `cam_from_world`: every landmark in front of the
  // camera and inside the image becomes a keypoint (pixel noise sigma
  // `pixel_noise`, `bit_flips` random descriptor bits flipped), in random
  // order, with exact depth. `landmark_of` (optional) receives the landmark
  // index of each keypoint.
  std::shared_ptr<Frame> MakeFrame(const SE3d& cam_from_world, double timestamp, unsigned seed,
                                   double pixel_noise = 0.5, int bit_flips = 8,
                                   std::vector<int>* landmark_of = nullptr) const;
};

// Frame i (at 30 Hz) of a smooth camera path through the room: ~1 m of
// translation, +-15 deg yaw, as cam_from_world.
SE3d SmoothRoomPath(int i);

}  // namespace dlslam::testing

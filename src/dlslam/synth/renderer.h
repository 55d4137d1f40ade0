#pragma once
// Renders one RGB-D frame of a scene: colour as a camera sees it, depth as a
// Kinect measures it, and per-pixel ground truth (true depth, mask), all from
// one z-buffer. Pure: no file I/O, no global state; the randomness (sensor
// noise) comes from the caller's engine.

#include <opencv2/core.hpp>

#include <cstdint>
#include <random>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"
#include "dlslam/synth/depth_noise.h"
#include "dlslam/synth/scene.h"

namespace dlslam::synth {

// Mask pixel: bits 0-6 the class (0 static, 1 person, 2 other movable
// object), bit 7 set when that surface moved more than the threshold.
inline constexpr std::uint8_t kMaskMovingBit = 128;
inline std::uint8_t MaskValue(int class_id, bool moving) {
  return static_cast<std::uint8_t>(class_id | (moving ? kMaskMovingBit : 0));
}
inline int MaskClass(std::uint8_t value) { return value & 0x7F; }
inline bool MaskMoving(std::uint8_t value) { return (value & kMaskMovingBit) != 0; }

struct RenderOptions {
  float near_m = 0.05f;              // nothing nearer than this is drawn [m]
  DepthNoiseOptions depth;           // the depth sensor model
  double colour_noise_sigma = 2.0;   // Gaussian noise per channel [grey levels]; 0 = off
  double lens_blur_sigma_px = 0.6;   // optical softness of the colour camera [px]; 0 = off
  int motion_blur_samples = 1;       // > 1: average that many instants over the exposure
  double exposure_s = 0.02;          // exposure time for motion blur [s]
  // A surface "moves" in a frame when some point of it travelled more than
  // moving_threshold_m during the last moving_interval_s.
  double moving_threshold_m = 0.003;
  double moving_interval_s = 1.0 / 30.0;
  double mip_bias = 0.0;             // texture level offset: > 0 blurrier, < 0 sharper

  // Throws dlslam::Error naming the offending value.
  void Check() const;
};

struct RenderedFrame {
  cv::Mat colour;      // CV_8UC3, BGR
  cv::Mat depth;       // CV_32FC1 [m], as the sensor reports it, 0 = no measurement
  cv::Mat true_depth;  // CV_32FC1 [m], exact z of the visible surface, 0 = nothing there
  cv::Mat mask;        // CV_8UC1, MaskValue(class, moving)
  SE3d world_from_cam;
  double scene_time = 0.0;  // [s] since the sequence started
};

// The camera pose at the start of the exposure is interpolated between
// `world_from_cam` and `previous_world_from_cam` (taken `frame_interval_s`
// earlier) when motion blur is on; without a previous pose there is none.
struct CameraState {
  SE3d world_from_cam;
  double scene_time = 0.0;  // [s]
  const SE3d* previous_world_from_cam = nullptr;
  double frame_interval_s = 1.0 / 30.0;
};

RenderedFrame RenderFrame(const Scene& scene, const CameraIntrinsics& camera, const CameraState& state,
                          const RenderOptions& options, std::mt19937& rng);

}  // namespace dlslam::synth

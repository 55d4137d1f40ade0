#pragma once
// Camera settings files in the ORB-SLAM3 YAML layouts (OpenCV FileStorage's
// YAML, "%YAML:1.0" first line), so that one file describes a camera for both.
// Read with yaml-cpp: bounded nesting, keys with their lines, no key twice.
//
// Old layout (ORB-SLAM2, ORB-SLAM3 before v1.0):
//   Camera.fx Camera.fy Camera.cx Camera.cy      required
//   Camera.k1 Camera.k2 Camera.p1 Camera.p2      required; Camera.k3 optional (0)
//   Camera.width Camera.height                   optional (0 = take from the images)
//   Camera.fps (30) Camera.bf (40) ThDepth (40) DepthMapFactor (none)
// v1.0 layout (File.version: "1.0"):
//   Camera1.fx .. Camera1.cy, Camera1.k1 .. Camera1.p2 (Camera1.k3), Camera.width,
//   Camera.height, Camera.fps, Stereo.b [m] (bf = b * fx) or Camera.bf,
//   Stereo.ThDepth, RGBD.DepthMapFactor; Camera.type must be "PinHole" if given.

#include <filesystem>

#include "dlslam/data/camera.h"

namespace dlslam::io {

struct CameraSettings {
  // width/height 0 when the file does not give them; depth_factor set from
  // DepthMapFactor when given (see has_depth_factor), else the struct default.
  CameraIntrinsics camera;
  bool has_image_size = false;
  bool has_depth_factor = false;
  double fps = 30.0;       // [Hz] Camera.fps
  double th_depth = 40.0;  // close/far depth threshold in baselines (ORB-SLAM ThDepth)
};

// Throws InputError naming the file (and the key's line) for: a missing,
// special (device, FIFO), over-1-MB or malformed file, a top level that is
// not a map, a key given twice, a missing required key, a value that is not
// wholly a finite number, a focal length / size / fps / depth factor out of
// range (camera.h), a camera that fails CameraIntrinsics::Check(), an
// unsupported Camera.type. camera.name is "settings:<file name>".
CameraSettings ReadSettingsFile(const std::filesystem::path& path);

// ReadSettingsFile(path).camera.
CameraIntrinsics ReadCameraSettings(const std::filesystem::path& path);

// Writes `camera` in the old layout (readable by ReadSettingsFile and by
// ORB-SLAM2/3), atomically. Reals always carry a decimal point, as
// ORB-SLAM3 requires. Throws dlslam::Error if camera.Check() fails.
void WriteCameraSettings(const std::filesystem::path& path, const CameraIntrinsics& camera,
                         double fps);

}  // namespace dlslam::io

#pragma once
// Which camera recorded a sequence folder, and its depth factor. Sources, in
// order (the first that applies wins):
//   camera: --settings FILE; --camera PRESET; <folder>/camera.yaml;
//           <folder>/camera-intrinsics.txt (3x3 K, as 7-Scenes); the folder
//           name (freiburg1/2/3 -> TUM preset, rgbd_bonn -> bonn); else an
//           InputError that says how to name the camera.
//   image size: the settings file, the preset, else the first colour image.
//   depth factor: --depth-factor; DepthMapFactor of the settings file; a
//           "depth factor N" comment in depth.txt; else 5000 (TUM, Bonn).

#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "dlslam/data/camera.h"

namespace dlslam::io {

struct CameraHints {
  std::string preset;                          // "" = none
  std::filesystem::path settings_file;         // "" = none
  double depth_factor = 0.0;                   // raw units per metre; 0 = none
  std::optional<double> depth_factor_comment;  // found in the depth list's comments
  std::filesystem::path depth_list;            // where that comment was (for messages)
};

struct CameraChoice {
  CameraIntrinsics camera;          // checked (Check() passed)
  std::string camera_source;        // e.g. "folder name 'rgbd_dataset_freiburg3_xyz'"
  std::string depth_factor_source;  // e.g. "comment in depth.txt"
  std::optional<double> fps;        // [Hz] when a settings file gives it
};

inline constexpr const char* kFolderSettingsName = "camera.yaml";
inline constexpr const char* kIntrinsicsMatrixName = "camera-intrinsics.txt";

// `first_image_size` is called only when no source gives the image size; it
// may throw InputError. Throws InputError when no camera can be found.
CameraChoice ResolveCamera(const std::filesystem::path& folder, const CameraHints& hints,
                           const std::function<cv::Size()>& first_image_size);

// camera-intrinsics.txt: three rows "fx 0 cx", "0 fy cy", "0 0 1". Width and
// height are left 0. Throws InputError (file:line) when it is not such a matrix.
CameraIntrinsics ReadIntrinsicsMatrix(const std::filesystem::path& path);

// "freiburg1".."freiburg3" or "bonn" when the folder's name contains
// freiburg1..3 or rgbd_bonn (case-insensitive).
std::optional<std::string> PresetFromFolderName(const std::filesystem::path& folder);

}  // namespace dlslam::io

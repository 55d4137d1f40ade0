#include "dlslam/io/camera_source.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "dlslam/io/settings.h"
#include "dlslam/io/text_table.h"
#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

std::string FolderName(const std::filesystem::path& folder) {
  auto path = std::filesystem::absolute(folder).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  return path.filename().string();
}

}  // namespace

CameraIntrinsics ReadIntrinsicsMatrix(const std::filesystem::path& path) {
  const TextTable table = ReadTextTable(path);
  if (table.rows.size() != 3) {
    throw InputError(path, 0, "expected a 3x3 camera matrix (3 rows), got {} rows",
                     table.rows.size());
  }
  double k[3][3];
  for (std::size_t r = 0; r < 3; ++r) {
    const TextRow& row = table.rows[r];
    if (row.fields.size() != 3) {
      throw InputError(path, row.line, "expected 3 numbers, got {}", row.fields.size());
    }
    for (std::size_t c = 0; c < 3; ++c)
      k[r][c] = ParseDouble(row.fields[c], path, row.line, "value");
  }
  const bool pinhole = k[0][1] == 0 && k[1][0] == 0 && k[2][0] == 0 && k[2][1] == 0 &&
                       k[2][2] == 1 && k[0][0] > 0 && k[1][1] > 0;
  if (!pinhole) {
    throw InputError(path, 0,
                     "not a pinhole camera matrix [fx 0 cx; 0 fy cy; 0 0 1] with fx, fy > 0");
  }
  CameraIntrinsics camera;
  camera.name = "intrinsics:" + path.filename().string();
  camera.fx = k[0][0];
  camera.fy = k[1][1];
  camera.cx = k[0][2];
  camera.cy = k[1][2];
  camera.width = camera.height = 0;
  return camera;
}

std::optional<std::string> PresetFromFolderName(const std::filesystem::path& folder) {
  std::string name = FolderName(folder);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  for (const char* preset : {"freiburg1", "freiburg2", "freiburg3"}) {
    if (name.find(preset) != std::string::npos) return std::string(preset);
  }
  if (name.find("rgbd_bonn") != std::string::npos) return std::string("bonn");
  return std::nullopt;
}

CameraChoice ResolveCamera(const std::filesystem::path& folder, const CameraHints& hints,
                           const std::function<cv::Size()>& first_image_size) {
  CameraChoice choice;
  std::optional<CameraSettings> settings;
  bool has_size = false;
  const auto folder_settings = folder / kFolderSettingsName;
  const auto intrinsics_file = folder / kIntrinsicsMatrixName;
  if (!hints.settings_file.empty()) {
    settings = ReadSettingsFile(hints.settings_file);
    choice.camera_source =
        fmt::format("settings file '{}' (--settings)", hints.settings_file.string());
  } else if (!hints.preset.empty()) {
    try {
      choice.camera = CameraPreset(hints.preset);
    } catch (const Error& e) {
      throw InputError(folder, 0, "--camera: {}", e.what());
    }
    choice.camera_source = fmt::format("preset '{}' (--camera)", hints.preset);
    has_size = true;
  } else if (std::filesystem::exists(folder_settings)) {
    settings = ReadSettingsFile(folder_settings);
    choice.camera_source = fmt::format("settings file '{}' in the folder", kFolderSettingsName);
  } else if (std::filesystem::exists(intrinsics_file)) {
    choice.camera = ReadIntrinsicsMatrix(intrinsics_file);
    choice.camera_source = fmt::format("'{}' in the folder (no distortion)", kIntrinsicsMatrixName);
  } else if (const auto preset = PresetFromFolderName(folder)) {
    choice.camera = CameraPreset(*preset);
    choice.camera_source =
        fmt::format("preset '{}' from the folder name '{}'", *preset, FolderName(folder));
    has_size = true;
  } else {
    throw InputError(folder, 0,
                     "cannot tell which camera recorded this sequence: pass --camera "
                     "fr1|fr2|fr3|bonn or --settings FILE (ORB-SLAM3 YAML), or put {} or {} in "
                     "the folder (see docs/datasets.md)",
                     kFolderSettingsName, kIntrinsicsMatrixName);
  }
  if (settings) {
    choice.camera = settings->camera;
    choice.fps = settings->fps;
    has_size = settings->has_image_size;
  }
  if (!has_size) {
    const cv::Size size = first_image_size();
    choice.camera.width = size.width;
    choice.camera.height = size.height;
  }

  const double default_factor = 5000.0;
  if (hints.depth_factor > 0) {
    if (settings && settings->has_depth_factor &&
        settings->camera.depth_factor != hints.depth_factor) {
      spdlog::warn("--depth-factor {} overrides DepthMapFactor {} of the settings file",
                   hints.depth_factor, settings->camera.depth_factor);
    }
    choice.camera.depth_factor = hints.depth_factor;
    choice.depth_factor_source = "--depth-factor";
  } else if (settings && settings->has_depth_factor) {
    choice.depth_factor_source = "DepthMapFactor of the settings file";
  } else if (hints.depth_factor_comment) {
    choice.camera.depth_factor = *hints.depth_factor_comment;
    choice.depth_factor_source =
        fmt::format("'depth factor' comment in {}", hints.depth_list.filename().string());
  } else {
    choice.camera.depth_factor = default_factor;
    choice.depth_factor_source = "default (TUM / Bonn: 5000 per metre)";
  }

  // Named by source before the camera as a whole is checked: 1e-300 or 1e300
  // gives inf or zero depth everywhere and a run that tracks nothing.
  const double factor = choice.camera.depth_factor;
  if (!IsPlausibleDepthFactor(factor)) {
    const std::string range = fmt::format("outside [{}, {}] raw units per metre", kMinDepthFactor, kMaxDepthFactor);
    if (choice.depth_factor_source == "--depth-factor") {
      throw InputError(folder, 0, "--depth-factor {} {}", factor, range);
    }
    throw InputError(hints.depth_list, 0, "depth factor {} of its 'depth factor' comment {}", factor, range);
  }

  try {
    choice.camera.Check();
  } catch (const Error& e) {
    throw InputError(folder, 0, "camera from {} is inconsistent with the images: {}",
                     choice.camera_source, e.what());
  }
  return choice;
}

}  // namespace dlslam::io

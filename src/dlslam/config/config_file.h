#pragma once
// One settings file for every option: `dlslam run --config FILE`,
// `dlslam config dump`. The file is YAML, nested as the modules are:
//
//   tracker:
//     min_local_map_inliers: 30   # [inliers] for a frame to count as tracked
//   dynamic:
//     mode: full
//
// ORB-SLAM3 settings keys work too, so that one ORB-SLAM3 settings file
// with our sections added configures everything: ORBextractor.nFeatures,
// scaleFactor, nLevels, iniThFAST, minThFAST set the orb section (which
// wins when both are given); Camera.*, DepthMapFactor and the other keys
// with a dot are the camera reader's (io/settings.h) and skipped here.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "dlslam/config/run_options.h"

namespace dlslam::config {

// Applies `file` on top of `options` (keys it does not name keep their
// values). Throws InputError with file:line for malformed YAML, a key given
// twice, an unknown key (with the closest known one), a value of the wrong
// type, a value out of range (the module's Check(), attributed to the key
// that made it fail).
void LoadConfig(const std::filesystem::path& file, RunOptions* options);

// Every option as a valid config file: key, value, unit and comment.
std::string DumpConfig(const RunOptions& options);

// Every option as nested JSON (the report's "options").
nlohmann::ordered_json ConfigJson(const RunOptions& options);

// Whether `file` has top-level keys of an ORB-SLAM3 settings file (a camera).
bool HasCameraKeys(const std::filesystem::path& file);

}  // namespace dlslam::config

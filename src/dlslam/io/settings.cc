#include "dlslam/io/settings.h"

#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "dlslam/io/file_util.h"
#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

// Line of "key:" in the file, for messages (FileStorage does not keep lines).
int LineOfKey(const std::filesystem::path& path, const std::string& key) {
  std::ifstream in(path);
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const auto first = text.find_first_not_of(" \t");
    if (first != std::string::npos && text.compare(first, key.size() + 1, key + ":") == 0) {
      return line;
    }
  }
  return 0;
}

std::string Describe(const cv::FileNode& node) {
  if (node.isString()) return fmt::format("text '{}'", node.string());
  if (node.isMap()) return "a map";
  if (node.isSeq()) return "a list";
  return "no value";
}

class SettingsFile {
 public:
  explicit SettingsFile(const std::filesystem::path& path) : path_(path) {
    if (!std::filesystem::exists(path)) throw InputError(path, 0, "settings file not found");
    if (std::filesystem::is_directory(path)) throw InputError(path, 0, "is a directory");
    if (std::filesystem::file_size(path) == 0) throw InputError(path, 0, "empty settings file");
    try {
      storage_.open(path.string(), cv::FileStorage::READ | cv::FileStorage::FORMAT_YAML);
    } catch (const cv::Exception& e) {
      // OpenCV 4.6's parser puts "<file>(<line>): <problem>" in e.func and
      // its own function name in e.err; other failures only have e.err.
      int line = 0;
      std::string problem = e.err;
      const std::string& where = e.func;
      const auto close = where.find("): ");
      const auto open = close == std::string::npos ? close : where.rfind('(', close);
      if (open != std::string::npos && close > open + 1 &&
          where.find_first_not_of("0123456789", open + 1) == close) {
        line = std::stoi(where.substr(open + 1, close - open - 1));
        problem = where.substr(close + 3);
      }
      throw InputError(path, line, "malformed settings file (OpenCV YAML, '%YAML:1.0' first): {}",
                       problem);
    }
    if (!storage_.isOpened()) {
      throw InputError(path, 0, "cannot read as an OpenCV YAML settings file");
    }
  }

  bool Has(const std::string& key) const { return !storage_[key].isNone(); }

  std::optional<double> Number(const std::string& key) const {
    const cv::FileNode node = storage_[key];
    if (node.isNone()) return std::nullopt;
    if (!node.isInt() && !node.isReal()) {
      throw InputError(path_, LineOfKey(path_, key), "key '{}': expected a number, got {}", key,
                       Describe(node));
    }
    const double value = node.isInt() ? static_cast<double>(static_cast<int>(node)) : node.real();
    if (!std::isfinite(value)) {
      throw InputError(path_, LineOfKey(path_, key), "key '{}': {} is not finite", key, value);
    }
    return value;
  }

  double Required(const std::string& key) const {
    if (auto value = Number(key)) return *value;
    throw InputError(path_, 0, "missing required key '{}'", key);
  }

  std::optional<double> Positive(const std::string& key) const {
    const auto value = Number(key);
    if (value && !(*value > 0)) {
      throw InputError(path_, LineOfKey(path_, key), "key '{}': {} must be positive", key, *value);
    }
    return value;
  }

  int Size(const std::string& key) const {
    const double value = *Positive(key);
    if (value != std::floor(value) || value > 1e6) {
      throw InputError(path_, LineOfKey(path_, key), "key '{}': {} is not an image size", key,
                       value);
    }
    return static_cast<int>(value);
  }

  std::string String(const std::string& key) const {
    const cv::FileNode node = storage_[key];
    if (node.isString()) return node.string();
    if (node.isReal() || node.isInt()) return fmt::format("{}", node.real());
    return {};
  }

 private:
  std::filesystem::path path_;
  cv::FileStorage storage_;
};

// Shortest text that reads back to the same double, with a decimal point.
std::string Real(double value) {
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

CameraSettings ReadSettingsFile(const std::filesystem::path& path) {
  const SettingsFile file(path);
  const std::string version = file.String("File.version");
  if (file.Has("File.version") && version != "1.0" && version != "1") {
    throw InputError(path, LineOfKey(path, "File.version"),
                     "unsupported File.version '{}' (expected \"1.0\" or none)", version);
  }
  const bool v1 = file.Has("File.version");
  if (file.Has("Camera.type") && file.String("Camera.type") != "PinHole") {
    throw InputError(path, LineOfKey(path, "Camera.type"),
                     "Camera.type '{}' is not supported (only PinHole)",
                     file.String("Camera.type"));
  }
  const std::string cam = v1 ? "Camera1." : "Camera.";

  CameraSettings settings;
  CameraIntrinsics& c = settings.camera;
  c.name = "settings:" + path.filename().string();
  c.fx = file.Required(cam + "fx");
  c.fy = file.Required(cam + "fy");
  c.cx = file.Required(cam + "cx");
  c.cy = file.Required(cam + "cy");
  file.Positive(cam + "fx");
  file.Positive(cam + "fy");
  c.k1 = file.Required(cam + "k1");
  c.k2 = file.Required(cam + "k2");
  c.p1 = file.Required(cam + "p1");
  c.p2 = file.Required(cam + "p2");
  c.k3 = file.Number(cam + "k3").value_or(0.0);

  settings.has_image_size = file.Has("Camera.width") || file.Has("Camera.height");
  if (settings.has_image_size) {
    c.width = file.Has("Camera.width") ? file.Size("Camera.width") : 0;
    c.height = file.Has("Camera.height") ? file.Size("Camera.height") : 0;
    if (c.width == 0) throw InputError(path, 0, "missing required key 'Camera.width'");
    if (c.height == 0) throw InputError(path, 0, "missing required key 'Camera.height'");
  } else {
    c.width = c.height = 0;
  }
  settings.fps = file.Positive("Camera.fps").value_or(30.0);
  if (auto bf = file.Positive("Camera.bf")) {
    c.bf = *bf;
  } else if (auto baseline = file.Positive("Stereo.b")) {
    c.bf = *baseline * c.fx;
  }
  settings.th_depth = file.Positive(file.Has("Stereo.ThDepth") ? "Stereo.ThDepth" : "ThDepth")
                          .value_or(settings.th_depth);
  const auto depth_factor =
      file.Positive(file.Has("RGBD.DepthMapFactor") ? "RGBD.DepthMapFactor" : "DepthMapFactor");
  settings.has_depth_factor = depth_factor.has_value();
  if (depth_factor) c.depth_factor = *depth_factor;

  if (settings.has_image_size) {
    try {
      c.Check();
    } catch (const Error& e) {
      throw InputError(path, 0, "inconsistent camera: {}", e.what());
    }
  }
  return settings;
}

CameraIntrinsics ReadCameraSettings(const std::filesystem::path& path) {
  return ReadSettingsFile(path).camera;
}

void WriteCameraSettings(const std::filesystem::path& path, const CameraIntrinsics& camera,
                         double fps) {
  camera.Check();
  DLSLAM_CHECK(std::isfinite(fps) && fps > 0, "fps {} must be positive", fps);
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "%YAML:1.0\n"
        << "# Camera settings (ORB-SLAM2/3 layout), written by DLSLAM for camera '" << camera.name
        << "'.\n# Pixels; Camera.bf = baseline [m] * fx; DepthMapFactor = raw depth per metre.\n"
        << "Camera.type: \"PinHole\"\n\n";
    out << "Camera.fx: " << Real(camera.fx) << "\nCamera.fy: " << Real(camera.fy)
        << "\nCamera.cx: " << Real(camera.cx) << "\nCamera.cy: " << Real(camera.cy) << "\n\n";
    out << "Camera.k1: " << Real(camera.k1) << "\nCamera.k2: " << Real(camera.k2)
        << "\nCamera.p1: " << Real(camera.p1) << "\nCamera.p2: " << Real(camera.p2)
        << "\nCamera.k3: " << Real(camera.k3) << "\n\n";
    out << "Camera.width: " << camera.width << "\nCamera.height: " << camera.height
        << "\nCamera.fps: " << Real(fps) << "\nCamera.bf: " << Real(camera.bf)
        << "\nCamera.RGB: 1\n\nThDepth: 40.0\nDepthMapFactor: " << Real(camera.depth_factor)
        << "\n";
  });
}

}  // namespace dlslam::io

#include "dlslam/io/settings.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "dlslam/io/file_util.h"
#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

constexpr std::uintmax_t kMaxSettingsBytes = 1u << 20;  // ORB-SLAM3's largest is ~10 KB

// A settings file read with yaml-cpp: it bounds the nesting depth (OpenCV's
// parser overflows the stack on 100,000 nested '['), keeps the line of every
// key, and lets us refuse a key given twice. ORB-SLAM3's "%YAML:1.0" first
// line and its !!opencv-matrix tags read as they are.
class SettingsFile {
 public:
  explicit SettingsFile(const std::filesystem::path& path) : path_(path) {
    const std::string text = ReadFileBytes(path, kMaxSettingsBytes, "a settings file");
    if (text.empty()) throw InputError(path, 0, "empty settings file");
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::DeepRecursion& e) {
      throw InputError(path, e.mark.is_null() ? 0 : e.mark.line + 1,
                       "malformed YAML: lists or maps nested deeper than {} levels", e.depth());
    } catch (const YAML::Exception& e) {
      throw InputError(path, e.mark.is_null() ? 0 : e.mark.line + 1, "malformed YAML: {}", e.msg);
    }
    if (root.IsNull()) throw InputError(path, 0, "no settings in the file (only comments?)");
    if (!root.IsMap()) {
      throw InputError(path, Line(root), "the top level must be 'key: value' lines, got {}",
                       Describe(root));
    }
    for (const auto& entry : root) {
      if (!entry.first.IsScalar()) {
        throw InputError(path, Line(entry.first), "a key must be a name, got {}", Describe(entry.first));
      }
      const std::string& key = entry.first.Scalar();
      const auto [it, added] = keys_.emplace(key, Entry{entry.second, Line(entry.first)});
      if (!added) {
        throw InputError(path, Line(entry.first), "key {} given twice (first on line {})", Quoted(key),
                         it->second.line);
      }
    }
  }

  bool Has(const std::string& key) const { return keys_.count(key) > 0; }

  std::optional<double> Number(const std::string& key) const {
    const auto it = keys_.find(key);
    if (it == keys_.end()) return std::nullopt;
    const YAML::Node& node = it->second.value;
    if (!node.IsScalar()) Fail(key, fmt::format("expected a number, got {}", Describe(node)));
    // The whole token as a double: no 32-bit wrap-around (4294967936 stays
    // itself and is refused as an image size), no trailing garbage.
    std::string text = node.Scalar();
    if (!text.empty() && text.front() == '+') text.erase(0, 1);
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
      Fail(key, fmt::format("expected a number, got {}", Describe(node)));
    }
    if (!std::isfinite(value)) Fail(key, fmt::format("{} is not finite", Quoted(node.Scalar())));
    return value;
  }

  double Required(const std::string& key) const {
    if (auto value = Number(key)) return *value;
    throw InputError(path_, 0, "missing required key '{}'", key);
  }

  // Number(key) within [low, high] when given.
  std::optional<double> InRange(const std::string& key, double low, double high,
                                std::string_view unit = "") const {
    const auto value = Number(key);
    if (value && !(*value >= low && *value <= high)) {
      Fail(key, fmt::format("{} outside [{}, {}]{}{}", *value, low, high, unit.empty() ? "" : " ", unit));
    }
    return value;
  }

  std::optional<double> Positive(const std::string& key, double high, std::string_view unit = "") const {
    const auto value = Number(key);
    if (value && !(*value > 0 && *value <= high)) {
      Fail(key, fmt::format("{} outside (0, {}]{}{}", *value, high, unit.empty() ? "" : " ", unit));
    }
    return value;
  }

  int Size(const std::string& key) const {
    const double value = *Number(key);
    if (value != std::floor(value) || !(value >= 1 && value <= kMaxImageSide)) {
      Fail(key, fmt::format("{} is not an image size (a whole number of pixels, 1..{})", value,
                            kMaxImageSide));
    }
    return static_cast<int>(value);
  }

  std::string String(const std::string& key) const {
    const auto it = keys_.find(key);
    return it != keys_.end() && it->second.value.IsScalar() ? it->second.value.Scalar() : std::string();
  }

  int LineOf(const std::string& key) const {
    const auto it = keys_.find(key);
    return it == keys_.end() ? 0 : it->second.line;
  }

  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    throw InputError(path_, LineOf(key), "key '{}': {}", key, what);
  }

 private:
  struct Entry {
    YAML::Node value;
    int line;
  };

  static int Line(const YAML::Node& node) { return node.Mark().is_null() ? 0 : node.Mark().line + 1; }

  static std::string Describe(const YAML::Node& node) {
    if (node.IsScalar()) return "text " + Quoted(node.Scalar());
    if (node.IsMap()) return "a map";
    if (node.IsSequence()) return "a list";
    return "no value";
  }

  std::filesystem::path path_;
  std::map<std::string, Entry> keys_;
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
    file.Fail("File.version", fmt::format("unsupported version {} (expected \"1.0\" or none)",
                                          Quoted(version)));
  }
  const bool v1 = file.Has("File.version");
  if (file.Has("Camera.type") && file.String("Camera.type") != "PinHole") {
    file.Fail("Camera.type", fmt::format("{} is not supported (only PinHole)", Quoted(file.String("Camera.type"))));
  }
  const std::string cam = v1 ? "Camera1." : "Camera.";

  CameraSettings settings;
  CameraIntrinsics& c = settings.camera;
  c.name = "settings:" + path.filename().string();
  c.fx = file.Required(cam + "fx");
  c.fy = file.Required(cam + "fy");
  c.cx = file.Required(cam + "cx");
  c.cy = file.Required(cam + "cy");
  file.InRange(cam + "fx", kMinFocal, kMaxFocal, "px");
  file.InRange(cam + "fy", kMinFocal, kMaxFocal, "px");
  file.InRange(cam + "cx", 0, kMaxImageSide, "px");
  file.InRange(cam + "cy", 0, kMaxImageSide, "px");
  c.k1 = file.Required(cam + "k1");
  c.k2 = file.Required(cam + "k2");
  c.p1 = file.Required(cam + "p1");
  c.p2 = file.Required(cam + "p2");
  c.k3 = file.Number(cam + "k3").value_or(0.0);

  settings.has_image_size = file.Has("Camera.width") || file.Has("Camera.height");
  if (settings.has_image_size) {
    if (!file.Has("Camera.width")) throw InputError(path, 0, "missing required key 'Camera.width'");
    if (!file.Has("Camera.height")) throw InputError(path, 0, "missing required key 'Camera.height'");
    c.width = file.Size("Camera.width");
    c.height = file.Size("Camera.height");
  } else {
    c.width = c.height = 0;
  }
  settings.fps = file.Positive("Camera.fps", 1000, "Hz").value_or(30.0);
  if (auto bf = file.Positive("Camera.bf", kMaxBf, "px m")) {
    c.bf = *bf;
  } else if (auto baseline = file.Positive("Stereo.b", 10, "m")) {
    c.bf = *baseline * c.fx;
  }
  const std::string th_depth = file.Has("Stereo.ThDepth") ? "Stereo.ThDepth" : "ThDepth";
  settings.th_depth = file.Positive(th_depth, 1e4).value_or(settings.th_depth);
  const std::string factor_key = file.Has("RGBD.DepthMapFactor") ? "RGBD.DepthMapFactor" : "DepthMapFactor";
  const auto depth_factor = file.InRange(factor_key, kMinDepthFactor, kMaxDepthFactor, "raw units per metre");
  settings.has_depth_factor = depth_factor.has_value();
  if (depth_factor) c.depth_factor = *depth_factor;

  // The whole camera (distortion against the image corners, the principal
  // point inside the image) once the size is known; otherwise the caller
  // checks it when the first image gives the size.
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

#include "dlslam/io/sequence_writer.h"

#include <fmt/format.h>

#include <cmath>
#include <regex>

#include "dlslam/io/file_util.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/settings.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/util/check.h"

namespace dlslam::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kListFiles[] = {"rgb.txt", "depth.txt", "mask.txt", "associations.txt", "groundtruth.txt",
                                      "camera.yaml"};
constexpr const char* kFrameDirs[] = {"rgb", "depth", "mask"};

bool IsEmptyDir(const fs::path& dir) { return fs::directory_iterator(dir) == fs::directory_iterator(); }

// Removes what an earlier run wrote: frames named like ours and our lists.
void RemoveEarlierRun(const fs::path& dir) {
  static const std::regex kFrameName(R"(\d+\.\d{6}\.png)");
  for (const char* sub : kFrameDirs) {
    if (!fs::is_directory(dir / sub)) continue;
    for (const auto& entry : fs::directory_iterator(dir / sub)) {
      if (entry.is_regular_file() && std::regex_match(entry.path().filename().string(), kFrameName)) {
        fs::remove(entry.path());
      }
    }
  }
  for (const char* name : kListFiles) fs::remove(dir / name);
}

void WriteList(const fs::path& path, const std::string& title, const std::string& description,
               const std::string& columns, const std::vector<std::string>& rows) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# " << title << "\n# file: '" << description << "'\n# " << columns << '\n';
    for (const std::string& row : rows) out << row << '\n';
  });
}

}  // namespace

SequenceWriter::SequenceWriter(const fs::path& dir, const CameraIntrinsics& camera,
                               const SequenceWriterOptions& options)
    : dir_(dir), camera_(camera), options_(options) {
  camera_.Check();
  DLSLAM_CHECK_GT(options_.fps, 0.0, "frame rate [Hz]");
  if (fs::exists(dir_) && !fs::is_directory(dir_)) throw InputError(dir_, 0, "exists and is not a directory");
  if (fs::is_directory(dir_) && !IsEmptyDir(dir_)) {
    if (fs::exists(dir_ / kMarkerFile)) {
      RemoveEarlierRun(dir_);
    } else if (!options_.force) {
      throw InputError(dir_, 0,
                       "is not empty and was not written by dlslam synth (no {}); choose another folder or "
                       "use --force to write into it (nothing there is deleted)",
                       kMarkerFile);
    }
  }
  std::error_code ec;
  for (const char* sub : kFrameDirs) {
    fs::create_directories(dir_ / sub, ec);
    if (ec) throw InputError(dir_ / sub, 0, "cannot create folder: {}", ec.message());
  }
  WriteFileAtomically(dir_ / kMarkerFile, [](std::ostream& out) {
    out << "Written by dlslam synth; writing again into this folder replaces its frames and lists.\n";
  });
}

void SequenceWriter::Add(double timestamp, const cv::Mat& colour, const cv::Mat& depth_m, const cv::Mat& mask,
                         const SE3d& world_from_cam) {
  const cv::Size size(camera_.width, camera_.height);
  DLSLAM_CHECK(colour.type() == CV_8UC3 && colour.size() == size, "colour must be 8-bit BGR {}x{}", size.width,
               size.height);
  DLSLAM_CHECK(depth_m.type() == CV_32FC1 && depth_m.size() == size, "depth must be float metres {}x{}",
               size.width, size.height);
  if (timestamps_.empty()) has_masks_ = !mask.empty();
  DLSLAM_CHECK_EQ(!mask.empty(), has_masks_, "every frame or none has a mask");
  if (has_masks_) DLSLAM_CHECK(mask.type() == CV_8UC1 && mask.size() == size, "mask must be 8-bit {}x{}", size.width, size.height);
  DLSLAM_CHECK(std::isfinite(timestamp) && timestamp >= 0, "timestamp {} must be finite and non-negative", timestamp);
  const std::string t = fmt::format("{:.6f}", timestamp);
  if (!trajectory_.empty()) {
    DLSLAM_CHECK(std::stod(t) > trajectory_.back().timestamp, "timestamp {} is not after the previous one {:.6f}",
                 t, trajectory_.back().timestamp);
  }
  WriteImage(dir_ / "rgb" / (t + ".png"), colour);
  WriteImage(dir_ / "depth" / (t + ".png"), DepthToRaw16(depth_m, camera_.depth_factor));
  if (has_masks_) WriteImage(dir_ / "mask" / (t + ".png"), mask);
  timestamps_.push_back(t);
  trajectory_.emplace_back(std::stod(t), world_from_cam);
}

void SequenceWriter::Finish() {
  std::vector<std::string> rgb, depth, mask, assoc;
  for (const std::string& t : timestamps_) {
    rgb.push_back(t + " rgb/" + t + ".png");
    depth.push_back(t + " depth/" + t + ".png");
    mask.push_back(t + " mask/" + t + ".png");
    assoc.push_back(t + " rgb/" + t + ".png " + t + " depth/" + t + ".png");
  }
  const std::string& d = options_.description;
  WriteList(dir_ / "rgb.txt", "color images", d, "timestamp filename", rgb);
  WriteList(dir_ / "depth.txt", "depth maps", d, "timestamp filename", depth);
  if (has_masks_) {
    WriteList(dir_ / "mask.txt",
              "ground-truth masks: value = class (0 static, 1 person, 2 other movable object) + 128 if moving",
              d, "timestamp filename", mask);
  }
  WriteList(dir_ / "associations.txt", "colour and depth pairs", d, "timestamp rgb_file timestamp depth_file",
            assoc);
  WriteTumTrajectory(dir_ / "groundtruth.txt", trajectory_,
                     "ground truth trajectory (world_from_cam)\nfile: '" + d + "'\ntimestamp tx ty tz qx qy qz qw");
  WriteCameraSettings(dir_ / "camera.yaml", camera_, options_.fps);
}

cv::Mat DepthToRaw16(const cv::Mat& depth_m, double factor) {
  DLSLAM_CHECK_EQ(depth_m.type(), CV_32FC1, "depth must be float metres");
  DLSLAM_CHECK_GT(factor, 0.0, "depth factor");
  cv::Mat raw(depth_m.size(), CV_16UC1);
  for (int y = 0; y < depth_m.rows; ++y) {
    const float* z = depth_m.ptr<float>(y);
    auto* r = raw.ptr<std::uint16_t>(y);
    for (int x = 0; x < depth_m.cols; ++x) {
      const double v = std::isfinite(z[x]) && z[x] > 0 ? std::round(z[x] * factor) : 0.0;
      r[x] = static_cast<std::uint16_t>(std::min(v, 65535.0));
    }
  }
  return raw;
}

}  // namespace dlslam::io

#pragma once
// Test helper: small TUM-layout sequence folders built in a temp directory.

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "dlslam/io/settings.h"
#include "tests/support/test_data.h"

namespace dlslam::io::testing {

class SequenceFolder {
 public:
  // A folder `name` (its name matters for camera resolution) in a fresh temp dir.
  explicit SequenceFolder(const std::string& name = "my_sequence")
      : root_(dlslam::testing::MakeTempDir("seq")), dir_(root_ / name) {
    std::filesystem::create_directories(dir_ / "rgb");
    std::filesystem::create_directories(dir_ / "depth");
  }
  ~SequenceFolder() { std::filesystem::remove_all(root_); }
  SequenceFolder(const SequenceFolder&) = delete;
  SequenceFolder& operator=(const SequenceFolder&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  const std::filesystem::path& root() const { return root_; }

  void WriteText(const std::string& relative, const std::string& text) const {
    std::ofstream(dir_ / relative, std::ios::binary) << text;
  }
  void WriteColor(const std::string& relative, cv::Size size) const {
    cv::Mat image(size, CV_8UC3);
    cv::randu(image, 0, 255);
    cv::imwrite((dir_ / relative).string(), image);
  }
  // Every pixel `raw`, except pixel (0, 0) which is 0 (no measurement).
  void WriteDepth(const std::string& relative, cv::Size size, int raw) const {
    cv::Mat depth(size, CV_16UC1, cv::Scalar(raw));
    depth.at<uint16_t>(0, 0) = 0;
    cv::imwrite((dir_ / relative).string(), depth);
  }

  // mask/i.png (8-bit, every pixel `value`) and mask.txt for frames
  // [0, n) of WriteValidSequence, at the colour times.
  void WriteMasks(int n, cv::Size size = {64, 48}, int value = 129) const {
    std::filesystem::create_directories(dir_ / "mask");
    std::string list = "# ground-truth masks\n# timestamp filename\n";
    for (int i = 0; i < n; ++i) {
      list += fmt::format("{:.6f} mask/{}.png\n", 1000.0 + i / 30.0, i);
      cv::imwrite((dir_ / fmt::format("mask/{}.png", i)).string(), cv::Mat(size, CV_8UC1, cv::Scalar(value)));
    }
    WriteText("mask.txt", list);
  }

  // n frames at 30 Hz: rgb/i.png, depth/i.png (raw 5000 + 10 i), depth 2 ms
  // after colour, camera.yaml for `size`.
  void WriteValidSequence(int n, cv::Size size = {64, 48}) const {
    std::string rgb = "# color images\n# timestamp filename\n";
    std::string depth = "# depth maps\n# timestamp filename\n";
    for (int i = 0; i < n; ++i) {
      const double t = 1000.0 + i / 30.0;
      rgb += fmt::format("{:.6f} rgb/{}.png\n", t, i);
      depth += fmt::format("{:.6f} depth/{}.png\n", t + 0.002, i);
      WriteColor(fmt::format("rgb/{}.png", i), size);
      WriteDepth(fmt::format("depth/{}.png", i), size, 5000 + 10 * i);
    }
    WriteText("rgb.txt", rgb);
    WriteText("depth.txt", depth);
    CameraIntrinsics camera;
    camera.name = "test";
    camera.width = size.width;
    camera.height = size.height;
    camera.fx = camera.fy = size.width;
    camera.cx = size.width / 2.0;
    camera.cy = size.height / 2.0;
    WriteCameraSettings(dir_ / "camera.yaml", camera, 30.0);
  }

 private:
  std::filesystem::path root_;
  std::filesystem::path dir_;
};

}  // namespace dlslam::io::testing

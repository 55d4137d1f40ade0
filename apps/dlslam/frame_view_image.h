#pragma once
// A frame as the dynamic stage saw it, drawn for people: the live view's
// frame and `dlslam run --removal-images`.

#include <filesystem>

#include <opencv2/core.hpp>

#include "dlslam/system/slam_system.h"

namespace dlslam::app {

// `colour` (BGR or grey) with the network prior's removal tinted red, what
// the removal adds to it (geometry) tinted blue, kept keypoints as green
// circles and removed ones as yellow circles. Masks of another size than
// the image are not drawn.
cv::Mat DrawFrameView(const cv::Mat& colour, const SlamSystem::FrameView& view);

// Writes `--removal-images` pictures into one folder, created if needed.
// Refuses a folder that holds files already: nothing written before is
// overwritten.
class RemovalImageWriter {
 public:
  RemovalImageWriter(std::filesystem::path folder, int every);
  // Writes frame `index` (every `every`-th) as <name>.jpg; throws Error
  // naming the file when it cannot.
  void Write(std::size_t index, const std::string& name, const cv::Mat& colour, const SlamSystem::FrameView& view);

 private:
  std::filesystem::path folder_;
  int every_;
};

}  // namespace dlslam::app

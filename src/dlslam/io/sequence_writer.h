#pragma once
// Writes an RGB-D sequence in the TUM RGB-D layout, as `dlslam synth` makes
// it: rgb/<t>.png (8-bit BGR), depth/<t>.png (16-bit, depth_factor per metre),
// mask/<t>.png (8-bit ground truth), rgb.txt, depth.txt, mask.txt,
// associations.txt, groundtruth.txt (world_from_cam at the frame times) and
// camera.yaml (ORB-SLAM3-style settings). <t> is the timestamp with 6
// decimals. A marker file says the folder is ours, so that writing again
// into it may replace earlier frames; other folders are never cleared.

#include <opencv2/core.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/data/trajectory.h"

namespace dlslam::io {

struct SequenceWriterOptions {
  double fps = 30.0;          // frame rate written to camera.yaml [Hz]
  std::string description;    // one line for the "# file:" comments, e.g. "dlslam synth walking_xyz seed 1"
  // Write into an existing non-empty folder that has no marker (our files
  // replace same-named ones; nothing else is deleted).
  bool force = false;
};

class SequenceWriter {
 public:
  static constexpr const char* kMarkerFile = ".dlslam_synth";

  // Prepares `dir` (creates it; in a folder with our marker, removes the
  // frames and lists of the earlier run). Throws InputError naming `dir` when
  // it is a file, or a non-empty folder without the marker and !force.
  SequenceWriter(const std::filesystem::path& dir, const CameraIntrinsics& camera,
                 const SequenceWriterOptions& options);

  // colour: CV_8UC3 BGR; depth: CV_32FC1 metres (0 = no measurement); mask:
  // CV_8UC1 or empty (no mask for this sequence). Sizes must match the camera.
  // Timestamps must increase.
  void Add(double timestamp, const cv::Mat& colour, const cv::Mat& depth_m, const cv::Mat& mask,
           const SE3d& world_from_cam);

  // Writes the lists, groundtruth.txt and camera.yaml.
  void Finish();

  const std::filesystem::path& dir() const { return dir_; }
  int frames() const { return static_cast<int>(timestamps_.size()); }

 private:
  std::filesystem::path dir_;
  CameraIntrinsics camera_;
  SequenceWriterOptions options_;
  std::vector<std::string> timestamps_;  // as written in the file names
  Trajectory trajectory_;
  bool has_masks_ = false;
};

// Metres to raw 16-bit depth: round(z * factor); 0 stays 0 (no measurement),
// values beyond 65535 are clamped.
cv::Mat DepthToRaw16(const cv::Mat& depth_m, double factor);

}  // namespace dlslam::io

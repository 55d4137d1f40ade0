#pragma once
// An RGB-D sequence folder in the TUM layout (TUM RGB-D, Bonn RGB-D Dynamic,
// 7-Scenes converted, `dlslam synth` output, your own recordings):
//   rgb.txt, depth.txt        "timestamp path" lists (or an association file)
//   rgb/, depth/              8-bit colour (PNG/JPEG), 16-bit depth PNGs
//   groundtruth.txt           optional, TUM trajectory (world_from_cam)
//   accelerometer.txt         optional, "timestamp ax ay az"
//   mask.txt, mask/           optional, per-pixel 8-bit labels ("timestamp path";
//                             `dlslam synth`'s ground truth), associated to the
//                             frames by time like depth
//   camera.yaml / camera-intrinsics.txt   optional camera (camera_source.h)
// Opening reads the lists and resolves the camera; images are read per frame,
// so a bad image fails only its own frame (TryLoadFrame).

#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/data/trajectory.h"
#include "dlslam/io/accelerometer.h"
#include "dlslam/io/image_list.h"

namespace dlslam::io {

struct RgbdSequenceOptions {
  // Largest |t_rgb - t_depth| [s] for an RGB and a depth image to form a
  // frame (strict; associate.py's default 0.02).
  double max_association_diff = 0.02;
  // Camera preset name ("fr1".."fr3", "freiburg1".."freiburg3", "bonn");
  // "" = resolve from the folder (camera_source.h).
  std::string camera_preset;
  // ORB-SLAM3-style settings file; "" = none. Wins over camera_preset.
  std::filesystem::path settings_file;
  // Raw depth units per metre; 0 = resolve (settings, depth.txt comment, 5000).
  double depth_factor = 0.0;
  // Association file ("t_rgb rgb t_depth depth"); "" = associate rgb.txt and
  // depth.txt. Its paths are relative to the sequence folder.
  std::filesystem::path associations_file;

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

// One associated RGB-D pair: where its images are and which lines named them.
struct RgbdFrameInfo {
  ListedImage rgb;
  ListedImage depth;
  std::optional<ListedImage> mask;  // from mask.txt, when it lists one near this time
  double timestamp() const { return rgb.timestamp; }  // the frame's time [s]
};

struct RgbdFrame {
  std::size_t index = 0;
  double timestamp = 0.0;        // [s] of the colour image
  double depth_timestamp = 0.0;  // [s]
  cv::Mat color;                 // CV_8UC3 BGR, camera width x height
  cv::Mat depth;                 // CV_32FC1 [m], 0 = no measurement
  cv::Mat mask;                  // CV_8UC1 labels as stored; empty when the frame has none
};

// TryLoadFrame's answer: a frame, or the InputError text of why not.
struct FrameLoadResult {
  std::optional<RgbdFrame> frame;
  std::string error;  // "list:line: depth image 'path': problem"; empty when loaded
  bool ok() const { return frame.has_value(); }
};

class RgbdSequence {
 public:
  // Throws InputError (file:line) for missing or malformed lists, a missing
  // or unreadable camera, malformed settings, or no associated frame.
  static RgbdSequence Open(const std::filesystem::path& folder,
                           const RgbdSequenceOptions& options = {});

  const std::filesystem::path& folder() const { return folder_; }
  const RgbdSequenceOptions& options() const { return options_; }
  const CameraIntrinsics& camera() const { return camera_; }
  const std::string& camera_source() const { return camera_source_; }
  const std::string& depth_factor_source() const { return depth_factor_source_; }
  std::optional<double> fps() const { return fps_; }  // from a settings file

  // The associated frames, sorted by time.
  const std::vector<RgbdFrameInfo>& frames() const { return frames_; }
  std::size_t size() const { return frames_.size(); }
  // rgb.txt / depth.txt as read; empty when an association file was given.
  const std::vector<ListedImage>& rgb_list() const { return rgb_list_; }
  const std::vector<ListedImage>& depth_list() const { return depth_list_; }
  // mask.txt as read (empty without one), and whether any frame got a mask.
  const std::vector<ListedImage>& mask_list() const { return mask_list_; }
  bool has_masks() const { return frames_with_mask_ > 0; }
  std::size_t frames_with_mask() const { return frames_with_mask_; }
  // groundtruth.txt / accelerometer.txt if the folder has them.
  const std::optional<Trajectory>& ground_truth() const { return ground_truth_; }
  const std::vector<AccelerometerSample>& accelerometer() const { return accelerometer_; }

  // Reads frame i (< size(); else dlslam::Error), with its mask if it has
  // one. Throws InputError naming the image and the list line for a missing,
  // empty, corrupt, 8-bit depth, 16-bit or multi-channel mask or wrongly
  // sized image.
  RgbdFrame LoadFrame(std::size_t i) const;
  // As LoadFrame, but a bad image is returned as an error instead of thrown,
  // so that a run can mark the frame lost and go on.
  FrameLoadResult TryLoadFrame(std::size_t i) const;

 private:
  RgbdSequence() = default;
  // Associates mask.txt's images to the frames by time.
  void AttachMasks(ImageList masks);

  std::filesystem::path folder_;
  RgbdSequenceOptions options_;
  CameraIntrinsics camera_;
  std::string camera_source_;
  std::string depth_factor_source_;
  std::optional<double> fps_;
  std::vector<RgbdFrameInfo> frames_;
  std::vector<ListedImage> rgb_list_;
  std::vector<ListedImage> depth_list_;
  std::vector<ListedImage> mask_list_;
  std::size_t frames_with_mask_ = 0;
  std::optional<Trajectory> ground_truth_;
  std::vector<AccelerometerSample> accelerometer_;
};

}  // namespace dlslam::io

#include "dlslam/io/sequence.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "dlslam/io/association.h"
#include "dlslam/io/camera_source.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/text_table.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

ImageSource SourceOf(const std::filesystem::path& folder, const ListedImage& image) {
  return {folder / image.path, image.list_file, image.line};
}

ImageList ReadRequiredList(const std::filesystem::path& folder, const char* name) {
  const auto path = folder / name;
  if (!std::filesystem::exists(path)) {
    throw InputError(path, 0,
                     "file not found: a TUM-layout sequence folder needs rgb.txt and depth.txt "
                     "(or pass an association file)");
  }
  ImageList list = ReadImageList(path);
  if (list.images.empty()) throw InputError(path, 0, "lists no images");
  return list;
}

}  // namespace

void RgbdSequenceOptions::Check() const {
  DLSLAM_CHECK(std::isfinite(max_association_diff) && max_association_diff > 0,
               "max_association_diff {} s must be positive", max_association_diff);
  DLSLAM_CHECK(std::isfinite(depth_factor) && depth_factor >= 0,
               "depth_factor {} must be positive (or 0 = from the sequence)", depth_factor);
}

RgbdSequence RgbdSequence::Open(const std::filesystem::path& folder,
                                const RgbdSequenceOptions& options) {
  options.Check();
  if (!std::filesystem::is_directory(folder)) {
    throw InputError(folder, 0, "sequence folder not found (or not a folder)");
  }
  RgbdSequence seq;
  seq.folder_ = folder;
  seq.options_ = options;

  CameraHints hints;
  hints.preset = options.camera_preset;
  hints.settings_file = options.settings_file;
  hints.depth_factor = options.depth_factor;
  hints.depth_list = folder / "depth.txt";
  if (!options.associations_file.empty()) {
    for (AssociatedImages& pair : ReadAssociationFile(options.associations_file)) {
      seq.frames_.push_back({std::move(pair.rgb), std::move(pair.depth), std::nullopt});
    }
    // Only the comments matter here; the lines are not checked.
    if (std::filesystem::exists(hints.depth_list)) {
      hints.depth_factor_comment =
          DepthFactorFromComments(ReadTextTable(hints.depth_list).comments);
    }
  } else {
    ImageList rgb = ReadRequiredList(folder, "rgb.txt");
    ImageList depth = ReadRequiredList(folder, "depth.txt");
    hints.depth_factor_comment = DepthFactorFromComments(depth.comments);
    std::vector<double> rgb_times, depth_times;
    for (const ListedImage& image : rgb.images) rgb_times.push_back(image.timestamp);
    for (const ListedImage& image : depth.images) depth_times.push_back(image.timestamp);
    for (const IndexPair& p :
         AssociateTimestamps(rgb_times, depth_times, 0.0, options.max_association_diff)) {
      seq.frames_.push_back({rgb.images[p.first], depth.images[p.second], std::nullopt});
    }
    seq.rgb_list_ = std::move(rgb.images);
    seq.depth_list_ = std::move(depth.images);
  }
  if (seq.frames_.empty()) {
    throw InputError(options.associations_file.empty() ? folder : options.associations_file, 0,
                     "no frames: no RGB image has a depth image within {} s",
                     options.max_association_diff);
  }

  const CameraChoice choice = ResolveCamera(
      folder, hints, [&] { return ReadImageSize(SourceOf(folder, seq.frames_.front().rgb)); });
  seq.camera_ = choice.camera;
  seq.camera_source_ = choice.camera_source;
  seq.depth_factor_source_ = choice.depth_factor_source;
  seq.fps_ = choice.fps;

  if (const auto masks = folder / "mask.txt"; std::filesystem::exists(masks)) {
    seq.AttachMasks(ReadImageList(masks));
  }
  if (const auto gt = folder / "groundtruth.txt"; std::filesystem::exists(gt)) {
    seq.ground_truth_ = ReadTumTrajectory(gt);
  }
  if (const auto acc = folder / "accelerometer.txt"; std::filesystem::exists(acc)) {
    seq.accelerometer_ = ReadAccelerometer(acc);
  }
  spdlog::info("sequence {}: {} frames; camera {} {}x{} from {}; depth factor {} from {}{}",
               folder.string(), seq.frames_.size(), seq.camera_.name, seq.camera_.width,
               seq.camera_.height, seq.camera_source_, seq.camera_.depth_factor,
               seq.depth_factor_source_,
               seq.mask_list_.empty() ? "" : fmt::format("; masks for {} frames", seq.frames_with_mask_));
  return seq;
}

void RgbdSequence::AttachMasks(ImageList masks) {
  std::vector<double> frame_times, mask_times;
  for (const RgbdFrameInfo& f : frames_) frame_times.push_back(f.timestamp());
  for (const ListedImage& image : masks.images) mask_times.push_back(image.timestamp);
  for (const IndexPair& p : AssociateTimestamps(frame_times, mask_times, 0.0, options_.max_association_diff)) {
    frames_[p.first].mask = masks.images[p.second];
    ++frames_with_mask_;
  }
  if (!masks.images.empty() && frames_with_mask_ == 0) {
    spdlog::warn("{}: no mask lies within {} s of a frame; masks ignored", masks.path.string(),
                 options_.max_association_diff);
  }
  mask_list_ = std::move(masks.images);
}

RgbdFrame RgbdSequence::LoadFrame(std::size_t i) const {
  DLSLAM_CHECK_LT(i, frames_.size(), "frame index out of range in {}", folder_.string());
  const RgbdFrameInfo& info = frames_[i];
  RgbdFrame frame;
  frame.index = i;
  frame.timestamp = info.rgb.timestamp;
  frame.depth_timestamp = info.depth.timestamp;
  frame.color = ReadColorImage(SourceOf(folder_, info.rgb), camera_.width, camera_.height);
  frame.depth = ReadDepthImage(SourceOf(folder_, info.depth), camera_.depth_factor, camera_.width,
                               camera_.height);
  if (info.mask) frame.mask = ReadMaskImage(SourceOf(folder_, *info.mask), camera_.width, camera_.height);
  return frame;
}

FrameLoadResult RgbdSequence::TryLoadFrame(std::size_t i) const {
  FrameLoadResult result;
  try {
    result.frame = LoadFrame(i);
  } catch (const InputError& e) {
    result.error = e.what();
  }
  return result;
}

}  // namespace dlslam::io

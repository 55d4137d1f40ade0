// dlslam info: what an RGB-D sequence folder holds, and whether it reads.
//   dlslam info --sequence DIR [--camera fr3] [--settings F] [--depth-factor F]
//               [--associations FILE] [--max-diff S] [--check-all]

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "dlslam/data/camera.h"
#include "commands.h"
#include "dlslam/io/association.h"
#include "dlslam/io/sequence.h"
#include "dlslam/util/check.h"

namespace dlslam::app {
namespace {

struct InfoArgs {
  std::string sequence;
  io::RgbdSequenceOptions options;
  std::string settings, associations;
  bool check_all = false;
};

void PrintTiming(const io::RgbdSequence& seq) {
  std::vector<double> gaps;
  for (std::size_t i = 1; i < seq.size(); ++i) {
    gaps.push_back(seq.frames()[i].timestamp() - seq.frames()[i - 1].timestamp());
  }
  const double first = seq.frames().front().timestamp(), last = seq.frames().back().timestamp();
  const double duration = last - first;
  fmt::print("time          {:.6f} .. {:.6f}: {:.3f} s", first, last, duration);
  if (gaps.empty()) {
    fmt::print(" (one frame)\n");
    return;
  }
  std::sort(gaps.begin(), gaps.end());
  fmt::print(", {:.2f} frames/s (gap median {:.1f} ms, largest {:.1f} ms)\n",
             static_cast<double>(seq.size() - 1) / duration, 1e3 * gaps[gaps.size() / 2],
             1e3 * gaps.back());
}

void PrintCamera(const io::RgbdSequence& seq) {
  const CameraIntrinsics& c = seq.camera();
  fmt::print("camera        {} {}x{}  fx {} fy {} cx {} cy {}\n", c.name, c.width, c.height, c.fx,
             c.fy, c.cx, c.cy);
  if (c.HasDistortion()) {
    fmt::print("              distortion k1 {} k2 {} p1 {} p2 {} k3 {}\n", c.k1, c.k2, c.p1, c.p2,
               c.k3);
  } else {
    fmt::print("              no distortion\n");
  }
  fmt::print("              from {}\n", seq.camera_source());
  fmt::print("depth factor  {} raw units per metre, from {}\n", c.depth_factor,
             seq.depth_factor_source());
}

void PrintGroundTruth(const io::RgbdSequence& seq, double max_diff) {
  if (!seq.ground_truth()) {
    fmt::print("ground truth  none (no groundtruth.txt)\n");
    return;
  }
  const Trajectory& gt = *seq.ground_truth();
  std::vector<double> frame_times, gt_times;
  for (const auto& f : seq.frames()) frame_times.push_back(f.timestamp());
  for (const auto& p : gt) gt_times.push_back(p.timestamp);
  const auto matched = io::AssociateTimestamps(frame_times, gt_times, 0.0, max_diff);
  fmt::print(
      "ground truth  {} poses, {:.6f} .. {:.6f} ({:.3f} s); {} of {} frames have a pose "
      "within {} s\n",
      gt.size(), gt.front().timestamp, gt.back().timestamp,
      gt.back().timestamp - gt.front().timestamp, matched.size(), seq.size(), max_diff);
}

void PrintFrame(const io::RgbdFrame& frame) {
  std::vector<float> valid;
  for (int r = 0; r < frame.depth.rows; ++r) {
    const float* row = frame.depth.ptr<float>(r);
    for (int c = 0; c < frame.depth.cols; ++c) {
      if (row[c] > 0) valid.push_back(row[c]);
    }
  }
  fmt::print("frame {:<7} t {:.6f}: colour {}x{} BGR, depth {:.1f}% valid", frame.index,
             frame.timestamp, frame.color.cols, frame.color.rows,
             100.0 * static_cast<double>(valid.size()) / static_cast<double>(frame.depth.total()));
  if (!valid.empty()) {
    std::sort(valid.begin(), valid.end());
    fmt::print(", min {:.3f} median {:.3f} max {:.3f} m", valid.front(), valid[valid.size() / 2],
               valid.back());
  }
  fmt::print("\n");
}

void RunInfo(InfoArgs args) {
  args.options.settings_file = args.settings;
  args.options.associations_file = args.associations;
  const io::RgbdSequence seq = io::RgbdSequence::Open(args.sequence, args.options);
  fmt::print("sequence      {}\n", seq.folder().string());
  if (args.associations.empty()) {
    fmt::print("lists         rgb.txt {} images, depth.txt {} images\n", seq.rgb_list().size(),
               seq.depth_list().size());
    fmt::print("associated    {} frames (|t_rgb - t_depth| < {} s); unmatched: {} rgb, {} depth\n",
               seq.size(), args.options.max_association_diff, seq.rgb_list().size() - seq.size(),
               seq.depth_list().size() - seq.size());
  } else {
    fmt::print("associated    {} frames from {}\n", seq.size(), args.associations);
  }
  PrintTiming(seq);
  PrintCamera(seq);
  PrintGroundTruth(seq, args.options.max_association_diff);
  if (!seq.accelerometer().empty()) {
    fmt::print("accelerometer {} samples\n", seq.accelerometer().size());
  }
  PrintFrame(seq.LoadFrame(0));  // throws (exit 1) if the first frame is bad

  if (!args.check_all) return;
  std::size_t failed = 0;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const io::FrameLoadResult result = seq.TryLoadFrame(i);
    if (result.ok()) continue;
    if (++failed <= 20) fmt::print("bad frame {}: {}\n", i, result.error);
  }
  fmt::print("checked       {} frames, {} unreadable\n", seq.size(), failed);
  if (failed > 0) throw Error(fmt::format("{} of {} frames could not be read", failed, seq.size()));
}

}  // namespace

void AddInfoCommand(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "What an RGB-D sequence folder (TUM layout) holds: frames, association, camera, "
      "depth factor, ground truth; reads the first frame");
  cmd->add_option("--sequence", args->sequence,
                  "Sequence folder (rgb.txt, depth.txt, rgb/, depth/)")
      ->required();
  cmd->add_option("--camera", args->options.camera_preset,
                  "Camera preset: fr1, fr2, fr3 (freiburg1..3), bonn");
  cmd->add_option("--settings", args->settings, "Camera settings file (ORB-SLAM3 YAML)");
  cmd->add_option("--depth-factor", args->options.depth_factor,
                  "Raw depth units per metre (TUM/Bonn 5000, millimetres 1000)")->check(RealNumber(kMinDepthFactor, kMaxDepthFactor));
  cmd->add_option(
      "--associations", args->associations,
      "Association file 't_rgb rgb/x.png t_depth depth/y.png' instead of rgb.txt/depth.txt");
  cmd->add_option("--max-diff", args->options.max_association_diff,
                  "Largest RGB/depth time difference in seconds")
      ->capture_default_str()->check(RealNumber(1e-6, 1000));
  cmd->add_flag("--check-all", args->check_all, "Read every frame; non-zero exit if any is bad");
  cmd->callback([args] { RunInfo(*args); });
}

}  // namespace dlslam::app

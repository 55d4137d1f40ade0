#pragma once
// SLAM on a sequence folder: `dlslam run` and the demo.

#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "dlslam/io/sequence.h"
#include "run_report.h"

namespace dlslam::app {

struct RunArgs {
  std::filesystem::path sequence;
  std::filesystem::path config;     // --config FILE: every option; the flags in `given` override it
  std::set<std::string> given;      // the flags given on the command line ("--mode", ...)
  std::filesystem::path out = "trajectory.txt";
  std::filesystem::path keyframes;
  // How each frame's pose was obtained; "" = beside `out` (traj.txt ->
  // traj.sources.txt).
  std::filesystem::path pose_sources;
  std::filesystem::path report;
  std::filesystem::path html;       // --html: the run as one web page
  int view_port = -1;               // --view[=PORT]: serve the run live; -1 = no
  double view_linger_s = 0.0;       // --view-linger: keep serving after the run [s]
  std::filesystem::path removal_images;  // --removal-images: each frame as the dynamic stage saw it
  int removal_images_every = 1;          // --removal-images-every: every k-th frame
  std::string mode = "orb";                // orb, semantic, geometry, full
  std::string geometry_search = "ant";     // exhaustive, ant
  std::string fusion = "union";            // union, geometry-confirms, semantic, geometry
  std::string semantic_masks;              // "gt", a folder, or "" (the network)
  std::filesystem::path semantic_model;    // ONNX file; "" = the shipped model
  int segment_every = 1;                   // segment every k-th frame
  bool async_masks = false;                // --async-masks: never wait for the network
  bool sequential = false;
  // --realtime[=RATE]: play the sequence as a live camera delivers it
  // (io::LivePlayback: each frame at its timestamp, at RATE x the camera's
  // speed, frames the system had no time for dropped); 0 = as fast as possible.
  double realtime_rate = 0.0;
  bool no_relocalization = false;  // --no-relocalization
  bool no_loop = false;            // --no-loop
  bool no_movables = false;        // --no-movables
  std::string vocabulary;          // --vocabulary; "" = the shipped one
  std::string bundle_solver = "lm";  // local bundle adjustment: "lm" or "ceres"
  std::size_t max_frames = 0;
  std::filesystem::path save_map;   // --save-map FILE.dlmap
  std::filesystem::path load_map;   // --load-map FILE.dlmap
  bool localize = false;            // --localize: track in the loaded map without extending it
  std::filesystem::path dense_map;  // --dense-map: the static model as a PLY point cloud
  double dense_voxel = 0.02;        // --dense-voxel [m]
  bool dense_with_dynamic = false;  // --dense-with-dynamic: fuse the removed regions too
  io::RgbdSequenceOptions sequence_options;
};

struct RunOutcome {
  RunStats stats;
  std::optional<RunEvaluation> evaluation;  // with ground truth
};

// traj.txt -> traj.sources.txt (any extension is replaced).
std::filesystem::path PoseSourcesPath(const std::filesystem::path& trajectory);
// One line per frame: "timestamp source", after a comment header.
void WritePoseSources(const std::filesystem::path& path, const std::vector<FramePoseSource>& sources);

// Runs, writes the trajectory (and keyframes, report when asked), logs a summary.
RunOutcome RunSequence(const RunArgs& args);

}  // namespace dlslam::app

// Dense depth odometry alone (optimize/depth_alignment.h) on a sequence:
// chains frame-to-frame alignments and writes the trajectory (TUM format),
// to see what the static scene's depth says on real sensor data.
//   build/bin/depth_odometry --sequence SEQ --out odo.txt [--frames N]
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>

#include "dlslam/io/sequence.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/optimize/depth_alignment.h"

using namespace dlslam;

int main(int argc, char** argv) {
  CLI::App app("Dense depth odometry");
  std::string sequence_path, out = "depth_odometry.txt";
  std::size_t frames = 0;
  int step = 4;
  app.add_option("--sequence", sequence_path)->required();
  app.add_option("--out", out);
  app.add_option("--frames", frames);
  app.add_option("--step", step);
  CLI11_PARSE(app, argc, argv);
  const io::RgbdSequence sequence = io::RgbdSequence::Open(sequence_path);
  DepthAlignmentOptions options;
  options.sample_step = step;
  const DepthAligner aligner(sequence.camera(), options);
  Trajectory trajectory;
  SE3d cam_from_world, velocity;
  PreparedDepth previous;
  bool has_previous = false;
  double total_ms = 0;
  int aligned = 0;
  const std::size_t n = frames ? std::min(frames, sequence.size()) : sequence.size();
  for (std::size_t i = 0; i < n; ++i) {
    const io::FrameLoadResult loaded = sequence.TryLoadFrame(i);
    if (!loaded.ok()) continue;
    const cv::Mat& depth = loaded.frame->depth;
    if (has_previous) {
      const auto t0 = std::chrono::steady_clock::now();
      const DepthAlignment a = aligner.Align(previous, depth, velocity);
      total_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      ++aligned;
      if (a.converged) {
        velocity = a.current_from_reference;
      }
      cam_from_world = velocity * cam_from_world;
      if (i % 25 == 0) fmt::print(stderr, "frame {} inliers {:.3f} iterations {} converged {}\n", i, a.inlier_fraction, a.iterations, a.converged);
    }
    trajectory.emplace_back(loaded.frame->timestamp, cam_from_world.Inverse());
    aligner.Prepare(depth, &previous);
    has_previous = true;
  }
  io::WriteTumTrajectory(out, trajectory);
  fmt::print(stderr, "{} alignments, {:.2f} ms each\n", aligned, aligned ? total_ms / aligned : 0.0);
}

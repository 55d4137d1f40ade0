#pragma once
// Trajectory files in the TUM format: "timestamp tx ty tz qx qy qz qw" per
// line, '#' comments. Lossless: timestamps are written with 6 decimals (as
// the TUM tools do) and every other value in the shortest form that reads
// back to the same double.

#include <filesystem>
#include <string>

#include "dlslam/data/trajectory.h"

namespace dlslam::io {

struct TrajectoryReadOptions {
  // A quaternion whose norm differs from 1 by more than this is normalised
  // (with one warning per file); smaller deviations (rounded files) are kept
  // as written, and SE3 normalises on use.
  double quaternion_norm_tolerance = 1e-3;
  // Refuse files with fewer poses than this.
  std::size_t min_poses = 1;
};

// Throws InputError naming file and line for: a missing file, a line that is
// not 8 numbers, a non-finite value, a zero quaternion, a timestamp smaller
// than the one before, fewer than min_poses poses. A timestamp equal to the
// one before replaces that pose (with a warning), as in the TUM tools, whose
// readers fill a dictionary keyed by timestamp.
Trajectory ReadTumTrajectory(const std::filesystem::path& path,
                             const TrajectoryReadOptions& options = {});

// Writes atomically (an existing file is replaced only once the new one is
// complete). `header` lines are written as '#' comments.
void WriteTumTrajectory(const std::filesystem::path& path, const Trajectory& trajectory,
                        const std::string& header = "timestamp tx ty tz qx qy qz qw");

}  // namespace dlslam::io

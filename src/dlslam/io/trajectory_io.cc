#include "dlslam/io/trajectory_io.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <sstream>

#include "dlslam/io/file_util.h"
#include "dlslam/io/text_table.h"
#include "dlslam/util/check.h"

namespace dlslam::io {

Trajectory ReadTumTrajectory(const std::filesystem::path& path, const TrajectoryReadOptions& options) {
  const TextTable table = ReadTextTable(path);
  Trajectory trajectory;
  trajectory.reserve(table.rows.size());
  int normalised = 0;
  int first_normalised_line = 0;
  int duplicates = 0;
  int first_duplicate_line = 0;
  for (const TextRow& row : table.rows) {
    if (row.fields.size() != 8) {
      throw InputError(path, row.line, "expected 8 values (timestamp tx ty tz qx qy qz qw), got {}",
                       row.fields.size());
    }
    static constexpr const char* kNames[8] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
    double v[8];
    for (int i = 0; i < 8; ++i) v[i] = ParseDouble(row.fields[i], path, row.line, kNames[i]);
    // Beyond these, differences and squares in ATE/RPE overflow; no camera
    // trajectory (or clock) comes near them.
    if (!(std::abs(v[0]) <= kMaxTimestamp)) {
      throw InputError(path, row.line, "timestamp {} beyond +-{:g} s", v[0], kMaxTimestamp);
    }
    for (int i = 1; i < 4; ++i) {
      if (!(std::abs(v[i]) <= kMaxCoordinate)) {
        throw InputError(path, row.line, "{} {} beyond +-{:g} m", kNames[i], v[i], kMaxCoordinate);
      }
    }
    StampedPose pose;
    pose.timestamp = v[0];
    pose.translation = Eigen::Vector3d(v[1], v[2], v[3]);
    pose.rotation = Eigen::Quaterniond(v[7], v[4], v[5], v[6]);
    // The norm from the components scaled by the largest: the norm of
    // (1e308, 0, 0, 0) overflows, its direction does not.
    const double largest = pose.rotation.coeffs().cwiseAbs().maxCoeff();
    if (largest < 1e-9) throw InputError(path, row.line, "quaternion is zero");
    const Eigen::Quaterniond scaled(pose.rotation.coeffs() / largest);
    const double norm = scaled.norm() * largest;
    if (std::abs(norm - 1.0) > options.quaternion_norm_tolerance) {
      pose.rotation = scaled.normalized();
      if (normalised++ == 0) first_normalised_line = row.line;
    }
    if (!trajectory.empty() && pose.timestamp == trajectory.back().timestamp) {
      // Real TUM ground truth repeats a timestamp now and then (fr3
      // walking_static, fr2 xyz); the TUM tools keep the last line, so do we.
      if (duplicates++ == 0) first_duplicate_line = row.line;
      trajectory.back() = pose;
      continue;
    }
    if (!trajectory.empty() && pose.timestamp < trajectory.back().timestamp) {
      throw InputError(path, row.line, "timestamp {:.6f} is not after the previous one {:.6f}",
                       pose.timestamp, trajectory.back().timestamp);
    }
    trajectory.push_back(pose);
  }
  if (normalised > 0) {
    spdlog::warn("{}:{}: normalised {} quaternion(s) whose norm was off by more than {}",
                 path.string(), first_normalised_line, normalised,
                 options.quaternion_norm_tolerance);
  }
  if (duplicates > 0) {
    spdlog::warn("{}:{}: {} repeated timestamp(s); kept the last pose of each, as the TUM tools do",
                 path.string(), first_duplicate_line, duplicates);
  }
  if (trajectory.size() < options.min_poses) {
    throw InputError(path, 0, "has {} pose(s), need at least {}", trajectory.size(), options.min_poses);
  }
  return trajectory;
}

void WriteTumTrajectory(const std::filesystem::path& path, const Trajectory& trajectory,
                        const std::string& header) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    std::istringstream lines(header);
    for (std::string line; std::getline(lines, line);) out << "# " << line << '\n';
    for (const StampedPose& p : trajectory) {
      const Eigen::Quaterniond& q = p.rotation;
      out << fmt::format("{:.6f} {} {} {} {} {} {} {}\n", p.timestamp, p.translation.x(),
                         p.translation.y(), p.translation.z(), q.x(), q.y(), q.z(), q.w());
    }
  });
}

}  // namespace dlslam::io

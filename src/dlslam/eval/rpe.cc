#include "dlslam/eval/rpe.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dlslam/eval/associate.h"
#include "dlslam/eval/closest_index.h"
#include "dlslam/eval/input_checks.h"
#include "dlslam/util/check.h"

namespace dlslam::eval {

DeltaUnit ParseDeltaUnit(std::string_view text) {
  if (text == "s") return DeltaUnit::kSeconds;
  if (text == "m") return DeltaUnit::kMeters;
  if (text == "rad") return DeltaUnit::kRadians;
  if (text == "deg") return DeltaUnit::kDegrees;
  if (text == "f") return DeltaUnit::kFrames;
  throw Error(fmt::format("unknown delta unit '{}' (expected s, m, rad, deg or f)", text));
}

std::string_view ToString(DeltaUnit unit) {
  switch (unit) {
    case DeltaUnit::kSeconds: return "s";
    case DeltaUnit::kMeters: return "m";
    case DeltaUnit::kRadians: return "rad";
    case DeltaUnit::kDegrees: return "deg";
    case DeltaUnit::kFrames: return "f";
  }
  return "?";
}

void RpeOptions::Check() const {
  DLSLAM_CHECK(std::isfinite(delta) && delta > 0.0, "delta must be > 0, got {}", delta);
  const int unit = static_cast<int>(delta_unit);
  DLSLAM_CHECK(unit >= 0 && unit <= static_cast<int>(DeltaUnit::kFrames),
               "delta unit {} is not one of s, m, rad, deg, f", unit);
  // Below one frame the closest index to i + delta is often i itself: pairs
  // of a pose with itself, an RPE of zero that means nothing. (Fractions
  // above 1 are fine: the TUM tool takes the closest index, as we do.)
  if (delta_unit == DeltaUnit::kFrames && !(delta >= 1.0)) {
    throw Error(fmt::format("RPE delta {} in frames (--delta-unit f) must be at least 1", delta));
  }
  DLSLAM_CHECK(std::isfinite(offset), "offset must be finite, got {}", offset);
  DLSLAM_CHECK(std::isfinite(scale) && scale > 0.0, "scale must be > 0, got {}", scale);
}

namespace {

// The angle of a rotation from its trace, clamped, as the TUM tools do.
double RotationAngle(const SE3d& t) {
  const double c = (t.rotationMatrix().trace() - 1.0) / 2.0;
  return std::acos(std::min(1.0, std::max(-1.0, c)));
}

// a^-1 * b.
SE3d Ominus(const SE3d& a, const SE3d& b) { return a.Inverse() * b; }

// Where each estimate pose lies along `unit`: the value that delta steps over.
std::vector<double> IndexAlong(const std::vector<SE3d>& poses, const std::vector<double>& stamps,
                               DeltaUnit unit) {
  if (unit == DeltaUnit::kSeconds) return stamps;
  std::vector<double> index(poses.size(), 0.0);
  if (unit == DeltaUnit::kFrames) {
    for (std::size_t k = 0; k < index.size(); ++k) index[k] = static_cast<double>(k);
    return index;
  }
  for (std::size_t k = 0; k + 1 < poses.size(); ++k) {
    const SE3d motion = Ominus(poses[k + 1], poses[k]);
    double step = 0.0;
    if (unit == DeltaUnit::kMeters) step = motion.translation().norm();
    if (unit == DeltaUnit::kRadians) step = RotationAngle(motion);
    if (unit == DeltaUnit::kDegrees) step = RotationAngle(motion) * 180.0 / std::numbers::pi;
    index[k + 1] = index[k] + step;
  }
  return index;
}

std::vector<SE3d> Poses(const Trajectory& trajectory) {
  std::vector<SE3d> poses;
  poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) poses.push_back(p.world_from_cam());
  return poses;
}

}  // namespace

RpeResult ComputeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
  options.Check();
  CheckEvaluable(gt, "ground truth");
  CheckEvaluable(est, "estimate");
  const std::vector<double> stamps_gt = Timestamps(gt);
  const std::vector<double> stamps_est = Timestamps(est);
  const double offset = options.offset;

  // Overlap: distinct estimate stamps reached by going est -> closest gt -> closest est.
  std::vector<std::size_t> reached;
  for (const double t : stamps_est) {
    const double t_gt = stamps_gt[FindClosestIndex(stamps_gt, t + offset)];
    reached.push_back(FindClosestIndex(stamps_est, t_gt - offset));
  }
  std::sort(reached.begin(), reached.end());
  if (std::unique(reached.begin(), reached.end()) - reached.begin() < 2) {
    throw Error(fmt::format(
        "no overlap in time between GT ({:.6f}..{:.6f}) and EST ({:.6f}..{:.6f}, offset {} s)",
        stamps_gt.front(), stamps_gt.back(), stamps_est.front(), stamps_est.back(), offset));
  }

  const std::vector<SE3d> poses_est = Poses(est);
  const std::vector<SE3d> poses_gt = Poses(gt);
  const std::vector<double> index = IndexAlong(poses_est, stamps_est, options.delta_unit);

  std::vector<double> gt_steps(stamps_gt.size() - 1);
  for (std::size_t k = 0; k + 1 < stamps_gt.size(); ++k) gt_steps[k] = stamps_gt[k + 1] - stamps_gt[k];
  const double gt_max_time_difference = 2.0 * Median(gt_steps);

  RpeResult result;
  std::vector<double> trans_errors;
  std::vector<double> rot_errors;
  const std::size_t n = est.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = FindClosestIndex(index, index[i] + options.delta);
    if (j == n - 1) continue;  // as the TUM tool: a pair never ends at the last pose
    const std::size_t gi = FindClosestIndex(stamps_gt, stamps_est[i] + offset);
    const std::size_t gj = FindClosestIndex(stamps_gt, stamps_est[j] + offset);
    if (std::abs(stamps_gt[gi] - (stamps_est[i] + offset)) > gt_max_time_difference ||
        std::abs(stamps_gt[gj] - (stamps_est[j] + offset)) > gt_max_time_difference) {
      continue;
    }
    SE3d est_motion = Ominus(poses_est[j], poses_est[i]);
    est_motion.translation() *= options.scale;
    const SE3d error = Ominus(est_motion, Ominus(poses_gt[gj], poses_gt[gi]));
    RpePair pair;
    pair.est_index_0 = i;
    pair.est_index_1 = j;
    pair.est_timestamp_0 = stamps_est[i];
    pair.est_timestamp_1 = stamps_est[j];
    pair.gt_timestamp_0 = stamps_gt[gi];
    pair.gt_timestamp_1 = stamps_gt[gj];
    pair.translation_error = error.translation().norm();
    pair.rotation_error_deg = RotationAngle(error) * 180.0 / std::numbers::pi;
    trans_errors.push_back(pair.translation_error);
    rot_errors.push_back(pair.rotation_error_deg);
    result.per_pair.push_back(pair);
  }
  if (result.per_pair.size() < 2) {
    throw Error(fmt::format(
        "only {} pose pair(s) {} {} apart have ground truth within {} s; need at least 2",
        result.per_pair.size(), options.delta, ToString(options.delta_unit),
        gt_max_time_difference));
  }
  result.pairs = result.per_pair.size();
  result.translation = ComputeErrorStats(trans_errors);
  result.rotation_deg = ComputeErrorStats(rot_errors);
  return result;
}

}  // namespace dlslam::eval

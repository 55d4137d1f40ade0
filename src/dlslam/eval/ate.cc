#include "dlslam/eval/ate.h"

#include <cmath>

#include "dlslam/eval/associate.h"
#include "dlslam/eval/input_checks.h"
#include "dlslam/util/check.h"

namespace dlslam::eval {

void AteOptions::Check() const {
  AssociateOptions{max_diff, offset}.Check();
  DLSLAM_CHECK(std::isfinite(scale) && scale > 0.0, "scale must be > 0, got {}", scale);
}

AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options) {
  options.Check();
  CheckEvaluable(gt, "ground truth");
  CheckEvaluable(est, "estimate");
  const std::vector<TimestampMatch> matches = Associate(gt, est, {options.max_diff, options.offset});
  if (matches.size() < 2) {
    throw Error(fmt::format(
        "no overlap in time between GT and EST within max-diff {} s (offset {} s): {} pose(s) "
        "matched; GT spans {:.6f}..{:.6f}, EST spans {:.6f}..{:.6f}",
        options.max_diff, options.offset, matches.size(), gt.front().timestamp,
        gt.back().timestamp, est.front().timestamp, est.back().timestamp));
  }
  std::vector<Eigen::Vector3d> gt_points;
  std::vector<Eigen::Vector3d> est_points;
  gt_points.reserve(matches.size());
  est_points.reserve(matches.size());
  for (const TimestampMatch& m : matches) {
    gt_points.push_back(gt[m.gt_index].translation);
    est_points.push_back(est[m.est_index].translation * options.scale);
  }
  AteResult result;
  result.pairs = matches.size();
  result.gt_from_est = AlignHorn(est_points, gt_points);
  std::vector<double> errors;
  errors.reserve(matches.size());
  result.per_pair.reserve(matches.size());
  for (std::size_t k = 0; k < matches.size(); ++k) {
    AtePair pair;
    pair.gt_timestamp = gt[matches[k].gt_index].timestamp;
    pair.est_timestamp = est[matches[k].est_index].timestamp;
    pair.gt_position = gt_points[k];
    pair.est_position_aligned = result.gt_from_est.Apply(est_points[k]);
    pair.error = (pair.est_position_aligned - pair.gt_position).norm();
    errors.push_back(pair.error);
    result.per_pair.push_back(pair);
  }
  result.error = ComputeErrorStats(errors);
  return result;
}

}  // namespace dlslam::eval

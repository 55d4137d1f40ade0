#pragma once
// Timestamp association as the TUM tools' associate.py does it: every pair
// (gt_i, est_j) with |t_gt - (t_est + offset)| < max_diff is a candidate; the
// candidates are taken greedily in the order (difference, t_gt, t_est), each
// timestamp at most once; the result is sorted by time.

#include <cstddef>
#include <span>
#include <vector>

#include "dlslam/data/trajectory.h"

namespace dlslam::eval {

struct AssociateOptions {
  // [s] Largest accepted |t_gt - (t_est + offset)| (strictly smaller). > 0.
  double max_diff = 0.02;
  // [s] Added to the estimate's timestamps before matching (its clock offset).
  double offset = 0.0;

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

struct TimestampMatch {
  std::size_t gt_index = 0;   // into the ground-truth stamps
  std::size_t est_index = 0;  // into the estimate's stamps
  bool operator==(const TimestampMatch&) const = default;
};

// Stamps strictly increasing (throws dlslam::Error otherwise). O((n + m) log)
// for the usual case of a few candidates per stamp; same result as comparing
// all n * m pairs.
std::vector<TimestampMatch> AssociateTimestamps(std::span<const double> gt_stamps,
                                                std::span<const double> est_stamps,
                                                const AssociateOptions& options);

std::vector<TimestampMatch> Associate(const Trajectory& gt, const Trajectory& est,
                                      const AssociateOptions& options);

// The timestamps of a trajectory, in order.
std::vector<double> Timestamps(const Trajectory& trajectory);

}  // namespace dlslam::eval

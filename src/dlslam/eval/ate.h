#pragma once
// Absolute trajectory error exactly as the TUM RGB-D benchmark's
// evaluate_ate.py: associate timestamps, scale the estimate's positions,
// align them rigidly to the ground truth (Horn), and take the distances.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

#include "dlslam/data/trajectory.h"
#include "dlslam/eval/horn.h"
#include "dlslam/eval/stats.h"

namespace dlslam::eval {

struct AteOptions {
  // [s] Largest accepted |t_gt - (t_est + offset)| when matching poses. > 0.
  double max_diff = 0.02;
  // [s] Added to the estimate's timestamps (its clock offset).
  double offset = 0.0;
  // [-] Multiplies the estimate's positions before alignment (monocular scale). > 0.
  double scale = 1.0;

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

struct AtePair {
  double gt_timestamp = 0.0;   // [s]
  double est_timestamp = 0.0;  // [s] as in the file (without offset)
  Eigen::Vector3d gt_position = Eigen::Vector3d::Zero();           // [m]
  Eigen::Vector3d est_position_aligned = Eigen::Vector3d::Zero();  // [m] R * scale * p + t
  double error = 0.0;                                               // [m]
};

struct AteResult {
  std::size_t pairs = 0;
  ErrorStats error;                  // [m] over the pairs
  RigidAlignment gt_from_est;        // maps scaled estimate positions onto the ground truth
  std::vector<AtePair> per_pair;     // in time order
};

// Throws dlslam::Error when a trajectory has fewer than 2 poses, bad values,
// or fewer than 2 poses match in time.
AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options = {});

}  // namespace dlslam::eval

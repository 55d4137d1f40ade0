#pragma once
// Checks shared by ATE and RPE on the trajectories they are given.

#include <string_view>

#include "dlslam/data/trajectory.h"

namespace dlslam::eval {

// Throws dlslam::Error unless `trajectory` has at least two poses, strictly
// increasing timestamps and only finite numbers; `what` names it ("ground
// truth", "estimate").
void CheckEvaluable(const Trajectory& trajectory, std::string_view what);

}  // namespace dlslam::eval

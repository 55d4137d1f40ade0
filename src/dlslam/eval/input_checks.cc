#include "dlslam/eval/input_checks.h"

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::eval {

void CheckEvaluable(const Trajectory& trajectory, std::string_view what) {
  if (trajectory.size() < 2) {
    throw Error(fmt::format("the {} trajectory has {} pose(s); evaluation needs at least 2", what,
                            trajectory.size()));
  }
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const StampedPose& p = trajectory[i];
    if (!std::isfinite(p.timestamp) || !p.translation.allFinite() ||
        !p.rotation.coeffs().allFinite() || p.rotation.norm() == 0.0) {
      throw Error(fmt::format("the {} pose [{}] at {:.6f} has a non-finite value or zero quaternion",
                              what, i, p.timestamp));
    }
    if (!(std::abs(p.timestamp) <= kMaxTimestamp) || !(p.translation.lpNorm<Eigen::Infinity>() <= kMaxCoordinate)) {
      throw Error(fmt::format("the {} pose [{}] has a timestamp beyond +-{:g} s or a coordinate beyond +-{:g} m",
                              what, i, kMaxTimestamp, kMaxCoordinate));
    }
    if (i > 0 && !(p.timestamp > trajectory[i - 1].timestamp)) {
      throw Error(fmt::format("the {} timestamps must increase: pose [{}] at {:.6f} follows {:.6f}",
                              what, i, p.timestamp, trajectory[i - 1].timestamp));
    }
  }
}

}  // namespace dlslam::eval

#pragma once
// Relative pose error with a fixed delta, exactly as the TUM RGB-D
// benchmark's evaluate_rpe.py --fixed_delta, except that every pose pair is
// used: the TUM tool draws a random subset of 10000 when there are more
// (identical results for estimates under 10000 poses).
//
// For estimate poses P (world_from_cam) and ground truth Q, with
// ominus(a, b) = a^-1 b, each pair (i, j) gives
//   E = ominus(scale(ominus(P_j, P_i), s), ominus(Q_j', Q_i'))
// where scale multiplies the translation by s and Q_i' is the ground-truth
// pose closest in time to P_i. Translation error |t(E)|, rotation error the
// angle of R(E).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "dlslam/data/trajectory.h"
#include "dlslam/eval/stats.h"

namespace dlslam::eval {

// What `delta` counts along the estimate: seconds, metres travelled, radians
// or degrees turned, or frames.
enum class DeltaUnit { kSeconds, kMeters, kRadians, kDegrees, kFrames };

// "s" | "m" | "rad" | "deg" | "f"; throws dlslam::Error for anything else.
DeltaUnit ParseDeltaUnit(std::string_view text);
std::string_view ToString(DeltaUnit unit);

struct RpeOptions {
  // [delta_unit] Distance between the two poses of a pair. > 0.
  double delta = 1.0;
  // Unit of delta.
  DeltaUnit delta_unit = DeltaUnit::kSeconds;
  // [s] Added to the estimate's timestamps (its clock offset).
  double offset = 0.0;
  // [-] Multiplies the estimate's relative translations (monocular scale). > 0.
  double scale = 1.0;

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

struct RpePair {
  std::size_t est_index_0 = 0;  // i: the pair starts here
  std::size_t est_index_1 = 0;  // j: closest to index(i) + delta
  double est_timestamp_0 = 0.0;  // [s] as in the file (without offset)
  double est_timestamp_1 = 0.0;  // [s]
  double gt_timestamp_0 = 0.0;   // [s]
  double gt_timestamp_1 = 0.0;   // [s]
  double translation_error = 0.0;   // [m]
  double rotation_error_deg = 0.0;  // [deg]
};

struct RpeResult {
  std::size_t pairs = 0;
  ErrorStats translation;   // [m]
  ErrorStats rotation_deg;  // [deg]
  std::vector<RpePair> per_pair;  // in the order of i
};

// Throws dlslam::Error when a trajectory has fewer than 2 poses or bad
// values, when the estimate does not overlap the ground truth in time, or
// when fewer than 2 pairs have ground truth close enough in time (2 * the
// median ground-truth interval).
RpeResult ComputeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options = {});

}  // namespace dlslam::eval

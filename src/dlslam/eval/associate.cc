#include "dlslam/eval/associate.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "dlslam/util/check.h"

namespace dlslam::eval {

void AssociateOptions::Check() const {
  DLSLAM_CHECK(std::isfinite(max_diff) && max_diff > 0.0, "max_diff must be > 0 s, got {}",
               max_diff);
  DLSLAM_CHECK(std::isfinite(offset), "offset must be finite, got {}", offset);
}

namespace {

void CheckIncreasing(std::span<const double> stamps, const char* what) {
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    if (!(stamps[i] > stamps[i - 1])) {
      throw Error(fmt::format("{} timestamps must increase: [{}] = {:.6f} follows {:.6f}", what,
                              i, stamps[i], stamps[i - 1]));
    }
  }
}

struct Candidate {
  double diff;
  std::size_t gt_index;
  std::size_t est_index;
};

}  // namespace

std::vector<TimestampMatch> AssociateTimestamps(std::span<const double> gt_stamps,
                                                std::span<const double> est_stamps,
                                                const AssociateOptions& options) {
  options.Check();
  CheckIncreasing(gt_stamps, "ground truth");
  CheckIncreasing(est_stamps, "estimate");

  // est + offset is non-decreasing in the index, so each gt stamp's
  // candidates lie in a window found by binary search. The window is wider
  // than max_diff (rounding of the shifted stamps) and the exact test below
  // is the one that decides, written as the TUM tool writes it.
  std::vector<Candidate> candidates;
  const auto shifted_less = [&](double est, double value) { return est + options.offset < value; };
  for (std::size_t i = 0; i < gt_stamps.size(); ++i) {
    const double a = gt_stamps[i];
    const double margin = 2.0 * options.max_diff + 1e-9 * std::max(1.0, std::abs(a));
    auto it = std::lower_bound(est_stamps.begin(), est_stamps.end(), a - margin, shifted_less);
    for (; it != est_stamps.end() && *it + options.offset <= a + margin; ++it) {
      const double diff = std::abs(a - (*it + options.offset));
      if (diff < options.max_diff) {
        candidates.push_back({diff, i, static_cast<std::size_t>(it - est_stamps.begin())});
      }
    }
  }
  // (diff, t_gt, t_est): stamps increase with the index, so indices order alike.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.diff, x.gt_index, x.est_index) < std::tie(y.diff, y.gt_index, y.est_index);
  });

  std::vector<bool> gt_used(gt_stamps.size(), false);
  std::vector<bool> est_used(est_stamps.size(), false);
  std::vector<TimestampMatch> matches;
  for (const Candidate& c : candidates) {
    if (gt_used[c.gt_index] || est_used[c.est_index]) continue;
    gt_used[c.gt_index] = true;
    est_used[c.est_index] = true;
    matches.push_back({c.gt_index, c.est_index});
  }
  std::sort(matches.begin(), matches.end(), [](const TimestampMatch& x, const TimestampMatch& y) {
    return x.gt_index < y.gt_index;
  });
  return matches;
}

std::vector<double> Timestamps(const Trajectory& trajectory) {
  std::vector<double> stamps;
  stamps.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) stamps.push_back(p.timestamp);
  return stamps;
}

std::vector<TimestampMatch> Associate(const Trajectory& gt, const Trajectory& est,
                                      const AssociateOptions& options) {
  return AssociateTimestamps(Timestamps(gt), Timestamps(est), options);
}

}  // namespace dlslam::eval

#include "dlslam/place/revisit_evaluation.h"

#include <cmath>
#include <cstdlib>

#include "dlslam/util/check.h"

namespace dlslam::place {

void RevisitCriteria::Check() const {
  DLSLAM_CHECK_GE(min_frame_gap, 1, "revisits: min_frame_gap must be at least 1 frame");
  DLSLAM_CHECK_GT(max_distance_m, 0.0, "revisits: max_distance_m must be positive");
  DLSLAM_CHECK(max_angle_deg > 0.0 && max_angle_deg <= 180.0, "revisits: max_angle_deg {} not in (0, 180]",
               max_angle_deg);
  DLSLAM_CHECK(accept_distance_m >= max_distance_m && accept_angle_deg >= max_angle_deg,
               "revisits: the acceptance tolerance ({} m, {} deg) must not be tighter than the revisit one ({} m, {} deg)",
               accept_distance_m, accept_angle_deg, max_distance_m, max_angle_deg);
}

RevisitEvaluation EvaluateRevisits(const std::vector<RevisitFrame>& frames, const RevisitCriteria& criteria) {
  criteria.Check();
  auto within = [](const RevisitFrame& a, const RevisitFrame& b, double distance_m, double angle_deg) {
    const SE3d relative = a.world_from_cam.Inverse() * b.world_from_cam;
    return relative.translation().norm() <= distance_m && relative.so3().Log().norm() <= angle_deg * M_PI / 180.0;
  };
  auto same_place = [&](const RevisitFrame& a, const RevisitFrame& b) {
    return within(a, b, criteria.max_distance_m, criteria.max_angle_deg);
  };
  auto accepted = [&](const RevisitFrame& a, const RevisitFrame& b) {
    return within(a, b, criteria.accept_distance_m, criteria.accept_angle_deg);
  };
  RevisitEvaluation result;
  double chance_sum = 0.0;
  for (const RevisitFrame& query : frames) {
    int far = 0, revisits = 0, acceptable = 0;
    const RevisitFrame* best = nullptr;
    double best_score = -1.0;
    for (const RevisitFrame& other : frames) {
      if (std::abs(other.index - query.index) < criteria.min_frame_gap) continue;
      ++far;
      revisits += same_place(query, other) ? 1 : 0;
      acceptable += accepted(query, other) ? 1 : 0;
      const double score = ScoreL1(query.bow, other.bow);
      if (score > best_score) {
        best_score = score;
        best = &other;
      }
    }
    if (revisits == 0) continue;
    ++result.queries;
    result.correct += accepted(query, *best) ? 1 : 0;
    chance_sum += static_cast<double>(acceptable) / far;
  }
  if (result.queries > 0) {
    result.precision_at_1 = static_cast<double>(result.correct) / result.queries;
    result.chance = chance_sum / result.queries;
  }
  return result;
}

}  // namespace dlslam::place

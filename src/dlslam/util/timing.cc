#include "dlslam/util/timing.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dlslam {

TimingSummary Summarize(std::vector<double> d) {
  TimingSummary s;
  s.count = d.size();
  if (d.empty()) return s;
  std::sort(d.begin(), d.end());
  const std::size_t n = d.size();
  s.median = n % 2 ? d[n / 2] : 0.5 * (d[n / 2 - 1] + d[n / 2]);
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n)));
  s.p95 = d[std::clamp<std::size_t>(rank, 1, n) - 1];
  s.max = d.back();
  s.total = std::accumulate(d.begin(), d.end(), 0.0);
  return s;
}

void StageTimings::Add(const std::string& stage, double ms) {
  std::lock_guard lock(mutex_);
  durations_[stage].push_back(ms);
}

std::map<std::string, TimingSummary> StageTimings::Summaries() const {
  std::lock_guard lock(mutex_);
  std::map<std::string, TimingSummary> out;
  for (const auto& [stage, d] : durations_) out[stage] = Summarize(d);
  return out;
}

}  // namespace dlslam

#include "dlslam/io/live_playback.h"

#include <cmath>
#include <thread>

#include "dlslam/util/check.h"

namespace dlslam::io {

LivePlayback::LivePlayback(double rate, double first_timestamp, std::function<Clock::time_point()> now,
                           std::function<void(Clock::time_point)> sleep_until)
    : rate_(rate), first_timestamp_(first_timestamp), now_(std::move(now)), sleep_until_(std::move(sleep_until)) {
  DLSLAM_CHECK(std::isfinite(rate) && rate > 0, "playback rate {} must be a positive number", rate);
  DLSLAM_CHECK(std::isfinite(first_timestamp), "first timestamp {} is not a number", first_timestamp);
  DLSLAM_CHECK(now_ != nullptr, "LivePlayback needs a clock");
  if (!sleep_until_) sleep_until_ = [](Clock::time_point t) { std::this_thread::sleep_until(t); };
  start_ = now_();
}

LivePlayback::Clock::time_point LivePlayback::Arrival(double timestamp) const {
  // Timestamps before the first (an unsorted list) arrive at once.
  const double seconds = std::max(0.0, (timestamp - first_timestamp_) / rate_);
  return start_ + std::chrono::round<Clock::duration>(std::chrono::duration<double>(seconds));
}

void LivePlayback::WaitForArrival(double timestamp) const {
  const Clock::time_point arrival = Arrival(timestamp);
  if (now_() < arrival) sleep_until_(arrival);
}

double LivePlayback::MsSinceArrival(double timestamp) const {
  return std::chrono::duration<double, std::milli>(now_() - Arrival(timestamp)).count();
}

}  // namespace dlslam::io

#pragma once
// Plays a recorded sequence as a live camera delivers it: each frame arrives
// at its timestamp on the wall clock (scaled by a rate), and a camera driver
// keeps only the newest frame, so a frame the system had no time for is
// overwritten by the next one and never seen. Runs at the camera's pace
// measure what a robot would get: latency from arrival to pose, and frames
// dropped, with the background threads (local mapping, the network) given
// the idle time a real camera leaves them. Any thread; no state but the clock.
//
//   LivePlayback live(/*rate=*/1.0, first_timestamp);
//   for (each frame i) {
//     if (has_next && live.Overwritten(next_timestamp)) { drop i; continue; }
//     live.WaitForArrival(timestamp);
//     ... track ...
//     latency_ms = live.MsSinceArrival(timestamp);
//   }

#include <chrono>
#include <functional>

namespace dlslam::io {

class LivePlayback {
 public:
  using Clock = std::chrono::steady_clock;
  // `rate`: playback speed (1 = the camera's, 0.5 = half of it), > 0. The
  // clock starts now, with the frame of `first_timestamp` arriving at once.
  // `now` and `sleep_until` replace the steady clock in tests.
  LivePlayback(double rate, double first_timestamp, std::function<Clock::time_point()> now = Clock::now,
               std::function<void(Clock::time_point)> sleep_until = nullptr);

  // When the frame of `timestamp` [s, the sequence's clock] arrives.
  Clock::time_point Arrival(double timestamp) const;
  // Blocks until that frame has arrived (returns at once when it has).
  void WaitForArrival(double timestamp) const;
  // The next frame (of `next_timestamp`) has arrived already: the driver
  // replaced the one before it, which the system never gets.
  bool Overwritten(double next_timestamp) const { return now_() >= Arrival(next_timestamp); }
  // Time since the frame of `timestamp` arrived [ms] (its latency once tracked).
  double MsSinceArrival(double timestamp) const;

 private:
  double rate_;
  double first_timestamp_;
  std::function<Clock::time_point()> now_;
  std::function<void(Clock::time_point)> sleep_until_;
  Clock::time_point start_;
};

}  // namespace dlslam::io

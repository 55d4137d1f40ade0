#include "dlslam/io/live_playback.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

using Clock = LivePlayback::Clock;
using std::chrono::milliseconds;

// A hand-moved clock: sleeping moves it to the wake-up time.
struct FakeClock {
  Clock::time_point now{};
  int sleeps = 0;
  LivePlayback Playback(double rate, double first) {
    return LivePlayback(
        rate, first, [this] { return now; },
        [this](Clock::time_point t) {
          ++sleeps;
          now = t;
        });
  }
};

TEST(LivePlayback, FramesArriveAtTheirTimestampsScaledByTheRate) {
  FakeClock clock;
  const LivePlayback live = clock.Playback(/*rate=*/0.5, /*first=*/100.0);
  EXPECT_EQ(live.Arrival(100.0), Clock::time_point{});
  EXPECT_EQ(live.Arrival(100.1) - Clock::time_point{}, milliseconds(200));  // half speed: 0.1 s takes 0.2 s
  EXPECT_EQ(live.Arrival(99.0), Clock::time_point{});                      // before the first: at once
}

TEST(LivePlayback, WaitsOnlyForFramesThatHaveNotArrived) {
  FakeClock clock;
  const LivePlayback live = clock.Playback(1.0, 0.0);
  live.WaitForArrival(0.0);
  EXPECT_EQ(clock.sleeps, 0);
  live.WaitForArrival(0.033);
  EXPECT_EQ(clock.sleeps, 1);
  EXPECT_NEAR(live.MsSinceArrival(0.033), 0.0, 1e-6);
  clock.now += milliseconds(12);  // tracking took 12 ms
  EXPECT_NEAR(live.MsSinceArrival(0.033), 12.0, 1e-6);
  live.WaitForArrival(0.033);  // arrived already
  EXPECT_EQ(clock.sleeps, 1);
}

TEST(LivePlayback, AFrameIsOverwrittenOnceTheNextOneHasArrived) {
  FakeClock clock;
  const LivePlayback live = clock.Playback(1.0, 0.0);
  clock.now += milliseconds(40);                 // the first frame took 40 ms
  EXPECT_FALSE(live.Overwritten(0.0666));        // frame 2 not there yet: frame 1 (0.033) is taken
  clock.now += milliseconds(30);
  EXPECT_TRUE(live.Overwritten(0.0666));         // both arrived while busy: frame 1 is gone
}

TEST(LivePlayback, RejectsARateThatIsNotPositive) {
  EXPECT_THROW(LivePlayback(0.0, 0.0), Error);
  EXPECT_THROW(LivePlayback(-1.0, 0.0), Error);
  EXPECT_THROW(LivePlayback(std::nan(""), 0.0), Error);
}

}  // namespace
}  // namespace dlslam::io

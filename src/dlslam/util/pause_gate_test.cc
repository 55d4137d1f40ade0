#include "dlslam/util/pause_gate.h"

#include <gtest/gtest.h>

#include <atomic>
#include <optional>
#include <thread>

namespace dlslam {
namespace {

// The worker finishes a step while a pause is waiting and asks for its next
// step at once (as local mapping with a full queue): the pause goes first.
TEST(PauseGate, AWaitingPauseGoesBeforeTheWorkersNextStep) {
  for (int round = 0; round < 50; ++round) {
    PauseGate gate;
    std::atomic<bool> paused_once{false};
    std::optional<PauseGate::Hold> step(gate.BeginStep());
    std::thread pauser([&] {
      const PauseGate::Hold pause = gate.Pause();
      paused_once.store(true);
    });
    while (!gate.pause_requested()) std::this_thread::yield();
    step.reset();
    const PauseGate::Hold next = gate.BeginStep();
    EXPECT_TRUE(paused_once.load()) << "round " << round << ": the worker took its next step first";
    pauser.join();
  }
}

TEST(PauseGate, PausesFromTwoThreadsTakeTurns) {
  PauseGate gate;
  std::atomic<int> holders{0};
  std::atomic<int> overlaps{0};
  const auto pauser = [&] {
    for (int i = 0; i < 500; ++i) {
      const PauseGate::Hold pause = gate.Pause();
      if (holders.fetch_add(1) != 0) overlaps.fetch_add(1);
      holders.fetch_sub(1);
    }
  };
  std::thread a(pauser), b(pauser);
  for (int i = 0; i < 500; ++i) {
    const PauseGate::Hold step = gate.BeginStep();
    if (holders.load() != 0) overlaps.fetch_add(1);
  }
  a.join();
  b.join();
  EXPECT_EQ(overlaps.load(), 0);
}

TEST(PauseGate, AMovedHoldReleasesOnce) {
  PauseGate gate;
  {
    PauseGate::Hold first = gate.Pause();
    const PauseGate::Hold moved = std::move(first);
  }
  const PauseGate::Hold step = gate.BeginStep();  // would wait forever if still paused
  SUCCEED();
}

}  // namespace
}  // namespace dlslam

#include "dlslam/util/pause_gate.h"

namespace dlslam {

PauseGate::Hold PauseGate::BeginStep() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return !paused_ && requests_ == 0; });
  stepping_ = true;
  return Hold(this, /*pause=*/false);
}

PauseGate::Hold PauseGate::Pause() {
  std::unique_lock lock(mutex_);
  ++requests_;
  changed_.wait(lock, [&] { return !paused_ && !stepping_; });
  --requests_;
  paused_ = true;
  return Hold(this, /*pause=*/true);
}

bool PauseGate::pause_requested() {
  const std::lock_guard lock(mutex_);
  return requests_ > 0;
}

void PauseGate::Release(bool pause) {
  {
    const std::lock_guard lock(mutex_);
    (pause ? paused_ : stepping_) = false;
  }
  changed_.notify_all();
}

}  // namespace dlslam
